"""Turn other planners' plan text into artiplan's :class:`~artiplan.semantics.plan.Plan`.

The readers live in :mod:`artiplan.semantics.plan_io`. ENHSP and Kairos apply actions that share
a time stamp one after the other; VAL (and artiplan's validator) applies them in parallel, and a
"stop X, start Y" pair at one instant is then a mutex violation. :func:`sequentialise` keeps the
planner's meaning by spreading such actions 1 ms apart, as the conventions prescribe for plans
meant in sequence; the validator then judges the result.
"""

from __future__ import annotations

import dataclasses

from artiplan.pddl.task import TRUE, Task
from artiplan.semantics.compiled import is_noop
from artiplan.semantics.plan import Plan, TimedAction
from artiplan.semantics.plan_io import parse_enhsp_output, parse_plan

#: Separation of actions meant in sequence at one instant [s] (> VAL's tolerance 0.001).
SEQUENCE_GAP = 0.001


def sequentialise(plan: Plan, gap: float = SEQUENCE_GAP) -> tuple[Plan, int]:
    """Spread actions with equal (or decreasing) times ``gap`` apart, in their order.

    Returns the new plan and how many actions moved. The plan's end moves with its last action.
    """
    actions: list[TimedAction] = []
    moved = 0
    for action in plan.actions:
        if actions and action.time < actions[-1].time + gap - 1e-9:
            action = dataclasses.replace(action, time=round(actions[-1].time + gap, 6))
            moved += 1
        actions.append(action)
    end = plan.end
    if end is not None and actions and end < actions[-1].time:
        end = actions[-1].time
    return dataclasses.replace(plan, actions=tuple(actions), end=end), moved


def plan_from_enhsp(text: str) -> tuple[Plan, int]:
    """A plan from ENHSP's printed output, sequentialised; and how many actions moved."""
    return sequentialise(parse_enhsp_output(text))


def plan_from_ipc(text: str) -> tuple[Plan, int]:
    """A plan in the IPC/VAL format (``t: (a) [d]``, ``T: @PlanEND``), sequentialised.

    Zero durations (Kairos writes ``[0.000]`` on instantaneous actions) are dropped.
    """
    plan = parse_plan(text, "<planner output>")
    instant = tuple(
        dataclasses.replace(a, duration=None) if a.duration == 0 else a for a in plan.actions
    )
    return sequentialise(dataclasses.replace(plan, actions=instant))


def plan_from_val(text: str) -> Plan:
    """A plan in VAL's format as artiplan writes it (no conversion needed)."""
    return parse_plan(text, "<artiplan plan>")


def close_at_end(plan: Plan, task: Task) -> Plan:
    """Make a peer's plan end where the peer says it ends, in a form VAL reads.

    ENHSP and Kairos state an end time (``@PlanEND``) after the last action: the goal is reached
    by waiting. VAL checks the goal at the last happening, so such a plan is closed with an
    always-applicable no-op action of the task (the encodings' ``observe``) at that time. Plans
    without a later end, or tasks without such an action, are returned unchanged.
    """
    last = max((a.time for a in plan.actions), default=0.0)
    if plan.end is None or plan.end <= last + 1e-9:
        return plan
    noop = next((a for a in task.actions if a.precondition == TRUE and is_noop(a)), None)
    if noop is None:
        return plan
    close = TimedAction(max(plan.end, last + SEQUENCE_GAP), noop.name, noop.args)
    return dataclasses.replace(plan, actions=(*plan.actions, close), end=None)
