"""artiplan's PDDL+ planner, exact in time.

Modules, in the order a planning call uses them (the dynamics, compiled task and validator
are :mod:`artiplan.semantics`'s kernel):

- ``api``: ``plan(domain, problem)`` / ``plan_task(task)`` -> ``PlanResult`` (status, plan,
  trajectory, statistics); restarts; validation of every plan by ``artiplan.semantics``.
- ``proofs``: proofs of unsolvability (relaxed reachability, fluent intervals).
- ``engine``, ``ops``, ``waits``: lazy greedy best-first search with a preferred-operator open
  list, its operators, and waits to the next critical time on the plan grid.
- ``heuristic``, ``sideeffects``, ``intervals``: the rate-aware numeric relaxation and its
  helpful actions; ``numeric``, ``motion``, ``secondorder``, ``profile``: the general one.
- ``invariants``, ``timing``: rescues of threatened invariants, timing repair of skeletons.
- ``improve``, ``separate``: after the first plan, bounded re-searches (expansion budget) for a
  better one, and pulling coincident crossings apart for stock VAL.
- ``limits``: time and memory limits checked in the search loop.
"""
