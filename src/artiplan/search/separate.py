"""Pull apart crossings that a plan's timing makes coincide (for stock VAL's sake).

Two objects crossing a boundary at one instant by their own motion (two links wrapping at
once) are exact for our validator, but stock VAL computes the two crossings a rounding error
apart and rejects the plan ("does not falsify its precondition", benchmarks/results/
semantics.md). A planner makes such instants itself: it stops two turns the same time after
an event, so two links end at the same distance from a boundary and a later turn carries them
over it together. For each such instant in turn (at most :data:`MAX_INSTANTS`), this step
shifts the plan's tail by a few milliseconds at one of the actions before it, keeps a shift
only if the validator accepts it with its margins and fewer coincident instants, and gives up
quietly otherwise (crossings that the initial dynamics make coincide cannot be moved by the
plan).
"""

from __future__ import annotations

from collections.abc import Callable

from artiplan.pddl.task import Task
from artiplan.records import replace
from artiplan.semantics.plan import Plan
from artiplan.semantics.results import Margins, margins_of
from artiplan.semantics.validator import ValidationReport

#: Shifts [s] tried, in order: above the 5e-4 s that VAL's rounding spreads apart (measured),
#: on the plan's 1e-6 s grid.
SHIFTS = (0.003, -0.003, 0.007, -0.007)
#: Actions tried per coincident instant, the latest before it first.
MAX_ACTIONS = 6
#: Coincident instants tried, in time order.
MAX_INSTANTS = 4


def shifted_tail(plan: Plan, index: int, delta: float) -> Plan:
    """``plan`` with its actions from ``index`` on ``delta`` [s] later (order kept)."""
    acts = list(plan.actions)
    for i in range(index, len(acts)):
        acts[i] = replace(acts[i], time=round(acts[i].time + delta, 6))
    return Plan(tuple(acts), end=plan.end)


def separate(
    task: Task, plan: Plan, report: ValidationReport, event_gap: float,
    validate: Callable[[Plan], ValidationReport], out_of_time: Callable[[], bool],
) -> tuple[Plan, ValidationReport] | None:
    """A shifted ``plan`` with fewer coincident crossings and its margins kept, or None.

    ``validate`` judges a candidate; ``out_of_time()`` stops the attempts early.
    """
    if report.trajectory is None:
        return None
    best: tuple[Plan, ValidationReport] | None = None
    margins = margins_of(task, plan, report.trajectory, event_gap)
    for instant in margins.coincident[:MAX_INSTANTS]:
        found = _separate_at(task, plan, margins, instant, event_gap, validate, out_of_time)
        if found is not None:
            plan, got, margins = found
            best = plan, got
    return best


def _separate_at(
    task: Task, plan: Plan, before: Margins, instant: float, event_gap: float,
    validate: Callable[[Plan], ValidationReport], out_of_time: Callable[[], bool],
) -> tuple[Plan, ValidationReport, Margins] | None:
    earlier = [i for i, a in enumerate(plan.actions) if a.time < instant - 1e-9]
    for index in reversed(earlier[-MAX_ACTIONS:]):
        for delta in SHIFTS:
            if plan.actions[index].time + delta < 0:
                continue
            if out_of_time():
                return None
            candidate = shifted_tail(plan, index, delta)
            got = validate(candidate)
            if not got.valid or got.trajectory is None:
                continue
            after = margins_of(task, candidate, got.trajectory, event_gap)
            if _better(before, after):
                return candidate, got, after
    return None


def _better(before: Margins, after: Margins) -> bool:
    """Fewer coincident instants, and the margins still what the planner aims for."""
    return len(after.coincident) < len(before.coincident) and (after.ok or not before.ok)
