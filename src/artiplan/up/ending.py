"""Where a plan without an end marker ends: VAL's rule or ENHSP's.

A PDDL+ plan in VAL's format ends at its last happening, and VAL checks the goal there
(``last-happening``). ENHSP prints plans that end by waiting (``-----waiting---- [t]``,
``@PlanEND``), and unified-planning's ``TimeTriggeredPlan`` has no place for that end: up-enhsp
drops it. ``first-goal`` reads such a plan as ENHSP means it: after the last action time goes
on (processes and events exactly, as the validator simulates them) and the plan ends at the
first instant the goal holds, within a horizon.

``auto`` picks ``last-happening`` when the problem has an action without effects (such an
action can mark the end, as the paper's ``observe`` does) and ``first-goal`` when it has none
(a plan could not say where it ends otherwise).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Task
from artiplan.semantics import Kernel, State, compile_task

END_RULES = ("auto", "last-happening", "first-goal")

#: Default horizon [s] of ``first-goal``: how long after the last action the goal may come.
DEFAULT_HORIZON = 3600.0

#: Candidate ends tried at most (each one is a full validation), and critical instants passed.
MAX_CANDIDATES = 20
MAX_INSTANTS = 10_000


def goal_times(task: Task, state: State, horizon: float = DEFAULT_HORIZON) -> Iterator[float]:
    """Instants [s] from ``state`` (the settled state after a plan's last happening) on at which
    the goal may start to hold as time passes, in order, rounded up to the plans' 6 decimals.

    Time passes one critical instant at a time (the kernel's: events and process switches,
    and the goal's own comparisons), so that an event failure later on (an event triggered
    twice) ends the search there without hiding a goal reached before it. The caller
    validates each candidate (the events of that instant may falsify it again).
    """
    ct = compile_task(task)
    kernel = Kernel(ct)
    items = ct.comps.items
    t, facts, values = state.time, state.facts, state.values
    stop, found = t + horizon, 0
    try:
        active, _ = kernel.flow(facts, values)
        for _ in range(MAX_INSTANTS):
            if ct.goal(facts, values):
                found += 1
                yield math.ceil(round(t * 1e6, 3)) / 1e6
                if found >= MAX_CANDIDATES:
                    return
            flow = kernel.flow_of(active, values)
            if not flow.moving:
                return
            goal = {c for c in ct.goal_comps if items[c].fluents & flow.changing}
            watched = tuple(sorted(goal | set(kernel.comps_for(flow, "dynamic"))))
            dt = kernel.next_change(values, flow, watched, stop - t)
            if dt is None:
                return
            facts, values, active = kernel.advance(t, facts, values, t + dt, [], active)
            t += dt
    except InvalidPlanError:
        return
