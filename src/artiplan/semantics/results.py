"""What a planning call returns, whoever planned: status, plan, trajectory, statistics.

Shared by artiplan's planner (``search``), the external backends (``backends``) and their
users (``execution``, ``bench``, ``up``), so that none of them imports another for it.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from enum import Enum

from artiplan.errors import ExitCode
from artiplan.pddl.task import Task
from artiplan.records import dataclass, field, names
from artiplan.semantics.compiled import guard_facts
from artiplan.semantics.plan import Plan, TimedEvent
from artiplan.semantics.trajectory import Trajectory
from artiplan.semantics.walks import robustness

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from typing import Any


class PlanStatus(Enum):
    """How a planning call ended."""

    SOLVED = "solved"
    UNSOLVABLE_PROVEN = "unsolvable"
    NO_PLAN = "no-plan"
    TIMEOUT = "timeout"
    MEMOUT = "memout"
    ERROR = "error"

    @property
    def exit_code(self) -> ExitCode:
        """The command-line exit code (shared/docs/conventions.md)."""
        return _EXIT[self]


_EXIT = {
    PlanStatus.SOLVED: ExitCode.OK,
    PlanStatus.UNSOLVABLE_PROVEN: ExitCode.UNSOLVABLE,
    PlanStatus.NO_PLAN: ExitCode.NO_PLAN,
    PlanStatus.TIMEOUT: ExitCode.TIME_LIMIT,
    PlanStatus.MEMOUT: ExitCode.MEMORY_LIMIT,
    PlanStatus.ERROR: ExitCode.INTERNAL,
}

#: A goal that holds by less than this at the plan's end [units of its values] has no margin.
GOAL_MARGIN_MIN = 1e-3


@dataclass(frozen=True)
class Margins:
    """How robust a validated plan is.

    Attributes:
        event_gap_s: The closest an action comes to an event [s] (None without events).
        goal_margin: How far the goal is from failing at the end, in the units of its values
            (e.g. deg; None when it reads no number).
        ok: All at least what the planner aims for (``note`` says what is missing).
        object_event_gap_s: The closest two events of one object (their first argument, e.g.
            a link) come at distinct times [s] (None when no object has two). Below VAL's
            event window (0.01 s) VAL fires the later one at the earlier one's happening,
            which can re-enable an event that already fired there ("Attempt to trigger event
            twice"); a statistic, not counted in ``ok`` (VAL accepts most such plans).
        coincident: Instants [s] at which events fired for two objects by two crossings of
            their own (two links wrapping at once), not at an action's time. VAL computes
            the two crossings a rounding error apart and rejects the plan ("does not falsify
            its precondition", benchmarks/results/semantics.md); not counted in ``ok``: the
            dynamics, not the plan's timing, often make them.
    """

    event_gap_s: float | None
    goal_margin: float | None
    ok: bool
    note: str = ""
    object_event_gap_s: float | None = None
    coincident: tuple[float, ...] = ()


def margins_of(task: Task, plan: Plan, trajectory: Trajectory, event_gap: float) -> Margins:
    """The margins of ``plan`` along its ``trajectory``; ``event_gap`` [s]: the gap aimed at.
    Re-arms (events that only clear guard facts, :func:`guard_facts`) are left out: nothing
    reads what they change, so an action or another object's event may come close."""
    quiet = {task.events[i].signature for i in guard_facts(task)[1]}
    events = [e for e in trajectory.events if e.signature not in quiet]
    gaps = [abs(a.time - e.time) for a in plan.actions for e in events]
    gap = min(gaps) if gaps else None
    final = trajectory.final_state
    margin = robustness(task.goal, final.facts, final.values) if final is not None else None
    pair = _object_event_gap(events)
    notes = []
    if gap is not None and gap < event_gap - 1e-9:
        notes.append(f"an action {gap:.6f} s from an event (wanted {event_gap:g} s)")
    if margin is not None and margin < GOAL_MARGIN_MIN:
        notes.append(f"the goal holds by only {margin:.2g} at the end")
    return Margins(None if gap is None else round(gap, 6),
                   None if margin is None or math.isinf(margin) else round(margin, 6),
                   not notes, "; ".join(notes),
                   None if pair is None else round(pair[0], 6),
                   _coincident(plan, events))


def _coincident(plan: Plan, events: list[TimedEvent]) -> tuple[float, ...]:
    """Instants (not an action's) at which events fired for several first arguments."""
    actions = {round(a.time, 6) for a in plan.actions}
    seen: dict[float, set[str]] = {}
    for e in events:
        t = round(e.time, 6)
        if e.args and t not in actions and not e.after_actions:
            seen.setdefault(t, set()).add(e.args[0])
    return tuple(sorted(t for t, objs in seen.items() if len(objs) > 1))


def _object_event_gap(events: list[TimedEvent]) -> tuple[float, str] | None:
    """The smallest time between consecutive events of one object at distinct times [s], and
    the object."""
    last: dict[str, float] = {}
    best: tuple[float, str] | None = None
    for e in sorted(events, key=lambda e: e.time):
        if not e.args:
            continue
        obj = e.args[0]
        prev = last.get(obj)
        gap = None if prev is None else e.time - prev
        if gap is not None and gap > 1e-6 and (best is None or gap < best[0]):
            best = (gap, obj)
        last[obj] = e.time
    return best


@dataclass
class PlanStats(Mapping[str, "Any"]):
    """Counters and timings of a planning call (typed; also readable as a mapping, e.g.
    ``stats["expanded"]``, for scripts and JSON).

    Counts: ``expanded``, ``generated``, ``evaluated``, ``duplicates``, ``undo_pruned``,
    ``invalid`` (successors an event loop made impossible), ``rejected`` (goal nodes the
    validator refused), ``pruned`` (by the improvement's bound), ``gap_pruned`` (actions an
    event would follow too soon), ``events``, ``boundary_flows``, ``numeric_flows``,
    ``attempts`` (restarts), ``repairs`` / ``repaired`` (timing repairs tried / that gave the
    plan), ``repair_evals`` (their trajectory simulations), ``reused`` (successors the
    improvement's searches took from one another instead of computing them again). Seconds:
    ``parse_s``, ``ground_s``, ``compile_s``, ``search_s``, ``heuristic_s``, ``validate_s``,
    ``improve_s``, ``separate_s``, ``total_s``. The plan:
    ``plan_length``, ``makespan`` [s], ``validated``, ``margins``, ``separated`` (its tail
    shifted to pull coincident crossings apart, :mod:`artiplan.search.separate`). The
    improvement phase: ``improve_*``, ``first_makespan``, ``first_length``.
    """

    expanded: int = 0
    generated: int = 0
    evaluated: int = 0
    duplicates: int = 0
    undo_pruned: int = 0
    invalid: int = 0
    rejected: int = 0
    pruned: int = 0
    gap_pruned: int = 0
    events: int = 0
    boundary_flows: int = 0
    numeric_flows: int = 0
    attempts: int = 0
    repairs: int = 0
    repaired: int = 0
    repair_evals: int = 0
    reused: int = 0
    parse_s: float = 0.0
    ground_s: float = 0.0
    compile_s: float = 0.0
    search_s: float = 0.0
    heuristic_s: float = 0.0
    validate_s: float = 0.0
    improve_s: float = 0.0
    separate_s: float = 0.0
    repair_s: float = 0.0
    total_s: float = 0.0
    plan_length: int | None = None
    makespan: float | None = None
    validated: bool = False
    separated: bool = False
    margins: Margins | None = None
    initial_events: list[str] = field(default_factory=list)
    rejected_reasons: list[str] = field(default_factory=list)
    improve_budget: int = 0
    improve_expanded: int = 0
    improve_probes: int = 0
    improve_candidates: int = 0
    improve_cut: bool = False
    improve_rejected: list[str] = field(default_factory=list)
    first_makespan: float | None = None
    first_length: int | None = None

    def add(self, counts: Mapping[str, float]) -> None:
        """Add counters (a search's, the kernel's) to the fields of the same name."""
        for k, v in counts.items():
            setattr(self, k, getattr(self, k) + v)

    def __getitem__(self, key: str) -> Any:
        if key not in _STAT_KEYS:
            raise KeyError(key)
        value = getattr(self, key)
        if isinstance(value, Margins):  # as dataclasses.asdict (its fields are scalars)
            return {name: getattr(value, name) for name in names(Margins)}
        return value

    def __iter__(self) -> Iterator[str]:
        return iter(_STAT_NAMES)

    def __len__(self) -> int:
        return len(_STAT_NAMES)


_STAT_NAMES = names(PlanStats)
_STAT_KEYS = frozenset(_STAT_NAMES)


@dataclass
class PlanResult:
    """The outcome of planning.

    Attributes:
        status: How the call ended.
        plan: The validated plan (only when ``SOLVED``), events included as predicted.
        trajectory: The validator's trajectory of the plan, if solved.
        stats: Counters and timings.
        message: Why, in one line, when not solved (the proof, the limit, the error).
    """

    status: PlanStatus
    plan: Plan | None = None
    trajectory: Trajectory | None = None
    stats: PlanStats = field(default_factory=PlanStats)
    message: str = ""
