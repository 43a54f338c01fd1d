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
from artiplan.semantics import (
    VAL_TOLERANCES,
    EventError,
    State,
    advance,
    crossing_time,
    next_critical_time,
    point_holds,
)

END_RULES = ("auto", "last-happening", "first-goal")

#: Default horizon [s] of ``first-goal``: how long after the last action the goal may come.
DEFAULT_HORIZON = 3600.0

#: Candidate ends tried at most (each one is a full validation), and critical instants passed.
MAX_CANDIDATES = 20
MAX_INSTANTS = 10_000


def goal_times(task: Task, state: State, horizon: float = DEFAULT_HORIZON) -> Iterator[float]:
    """Instants [s] from ``state`` (the settled state after a plan's last happening) on at which
    the goal may start to hold as time passes, in order, rounded up to the plans' 6 decimals.

    Time passes one critical instant at a time (events and process switches, exactly, as the
    validator lets it pass), so that an event failure later on (an event triggered twice) ends
    the search there without hiding a goal reached before it. A candidate is where the goal
    holds at the start of a flow or becomes true along it; the caller validates each (the
    events of that instant may falsify it again).
    """
    stop = state.time + horizon
    found = 0
    try:
        flow = advance(task, state, state.time, VAL_TOLERANCES).flow
        for _ in range(MAX_INSTANTS):
            assert flow is not None
            left = stop - state.time
            step = None if flow.is_static else next_critical_time(task, flow, left, VAL_TOLERANCES)
            span = left if step is None else step
            if point_holds(task.goal, flow, 0.0, VAL_TOLERANCES):
                hit: float | None = 0.0
            elif flow.is_static or span <= 0:
                hit = None
            else:
                hit = crossing_time(task.goal, flow, span, VAL_TOLERANCES)
            if hit is not None:
                found += 1
                yield math.ceil(round((state.time + hit) * 1e6, 3)) / 1e6
                if found >= MAX_CANDIDATES:
                    return
            if step is None:
                return
            res = advance(task, state, state.time + step, VAL_TOLERANCES, flow=flow)
            state, flow = res.state, res.flow
    except (EventError, InvalidPlanError):
        return
