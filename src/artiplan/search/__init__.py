"""artiplan's PDDL+ planner, exact in time.

Modules, in the order a planning call uses them:

- ``api``: ``plan(domain, problem)`` / ``plan_task(task)`` -> ``PlanResult`` (status, plan,
  trajectory, statistics); restarts; validation of every plan by ``artiplan.semantics``.
- ``compiled``: the task's conditions and effects as generated Python functions.
- ``reachability``: proofs of unsolvability (relaxed reachability, fluent intervals).
- ``flow``, ``dynamics``, ``rightlimit``: exact polynomial flows, events at their exact times,
  waits to the next critical time, the validator's rules at boundaries.
- ``heuristic``, ``sideeffects``, ``intervals``: the rate-aware numeric relaxation and its
  helpful actions.
- ``engine``: lazy greedy best-first search with a preferred-operator open list.
- ``improve``: after the first plan, bounded re-searches (expansion budget) for a shorter one.
- ``limits``: time and memory limits checked in the search loop.
"""
