"""artiplan's planner: ``plan(domain, problem) -> PlanResult``.

The pipeline, each phase timed: load (parse + ground) -> compile -> prove unsolvable? ->
search (greedy best-first in exact time, :mod:`artiplan.search.engine`) -> extract the timed plan
-> validate it with :func:`artiplan.semantics.validate` (VAL's rules) -> search on for a shorter
plan within an expansion budget (:mod:`artiplan.search.improve`), validated the same way. A plan
the validator rejects is never returned as solved: that is a bug, reported as ``ERROR`` with the
reason.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from artiplan.errors import ExitCode, InvalidPlanError, UsageError
from artiplan.pddl.task import Task
from artiplan.search.engine import Search, SearchConfig, SearchOutcome, initial_node
from artiplan.search.heuristic import HeuristicConfig, RateHeuristic
from artiplan.search.improve import improve
from artiplan.search.limits import LimitReached, Limits
from artiplan.search.reachability import prove_unsolvable
from artiplan.semantics.compiled import CompiledTask, compile_task
from artiplan.semantics.kernel import Kernel
from artiplan.semantics.plan import Plan, TimedAction, TimedEvent


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


@dataclass
class PlanResult:
    """The outcome of planning.

    Attributes:
        status: How the call ended.
        plan: The validated plan (only when ``SOLVED``), events included as predicted.
        trajectory: The validator's trajectory of the plan (``semantics.Trajectory``), if solved.
        stats: expanded, generated, evaluated, duplicates, events, fallback_steps (counts);
            parse_s, ground_s, compile_s, heuristic_s, search_s, validate_s, total_s (seconds);
            plan_length, makespan [s].
        message: Why, in one line, when not solved (the proof, the limit, the error).
    """

    status: PlanStatus
    plan: Plan | None = None
    trajectory: Any = None
    stats: dict[str, Any] = field(default_factory=dict)
    message: str = ""


OPTIONS = {
    "epsilon": "separation of successive actions [s] (default 0.001)",
    "time_weight": "heuristic cost of one second, in actions (default 0.1)",
    "goal_margin": "time [s] a goal wait runs on past the goal boundary (default 0.01)",
    "value_precision": "decimals of values in duplicate detection (default 6)",
    "validate": "check the plan with artiplan.semantics.validate (default True)",
    "improve": "search on for a shorter plan within an expansion budget (default True)",
}


def plan(
    domain: str | Path, problem: str | Path, *, time_limit: float | None = None,
    memory_limit: float | None = None, on_progress: Progress | None = None, **options: Any,
) -> PlanResult:
    """Plan for a PDDL+ domain and problem (paths or PDDL text); see :func:`plan_task`.

    ``time_limit`` [s] covers parsing and grounding too; ``memory_limit`` [MB].
    """
    from artiplan.pddl import load_task

    t0 = time.perf_counter()
    task = load_task(str(domain) if isinstance(domain, Path) else domain,
                     str(problem) if isinstance(problem, Path) else problem)
    load_s = time.perf_counter() - t0
    remaining = None if time_limit is None else max(0.0, time_limit - load_s)
    result = plan_task(task, time_limit=remaining, memory_limit=memory_limit,
                       on_progress=on_progress, **options)
    result.stats["ground_s"] = task.stats.seconds
    result.stats["parse_s"] = max(0.0, load_s - task.stats.seconds)
    result.stats["total_s"] = result.stats.get("total_s", 0.0) + load_s
    return result


#: ``on_progress(elapsed [s], statistics so far)``: called every 2 s of a long planning call.
Progress = Callable[[float, dict[str, Any]], None]


def plan_task(
    task: Task, *, time_limit: float | None = None, memory_limit: float | None = None,
    on_progress: Progress | None = None, **options: Any,
) -> PlanResult:
    """Plan for a grounded task under the limits (``time_limit`` [s], ``memory_limit`` [MB]).

    The limits cover the validation of the plans found too (it can take seconds on long
    chains); ``on_progress`` is called about every 2 s with the counters so far.
    """
    unknown = set(options) - set(OPTIONS)
    if unknown:
        raise UsageError(f"unknown planner option(s) {sorted(unknown)}; valid: {sorted(OPTIONS)}")
    stats: dict[str, Any] = {}
    running: list[Search] = []  # the search under way, whose counters progress lines show

    def report(elapsed: float) -> None:
        assert on_progress is not None
        now = dict(stats)
        for k, v in (running[-1].stats.items() if running else ()):
            now[k] = now.get(k, 0) + v
        on_progress(elapsed, now)

    limits = Limits(time_limit, memory_limit, on_progress=report if on_progress else None)
    t0 = time.perf_counter()
    try:
        result = _plan(task, limits, stats, options, running)
    except LimitReached as exc:
        status = PlanStatus.TIMEOUT if exc.kind == "time" else PlanStatus.MEMOUT
        result = PlanResult(status, message=str(exc))
    except MemoryError:
        result = PlanResult(PlanStatus.MEMOUT, message="out of memory (MemoryError)")
    except InvalidPlanError as exc:
        result = PlanResult(PlanStatus.ERROR, message=str(exc))
    result.stats = {**stats, **result.stats, "total_s": time.perf_counter() - t0}
    return result


#: Restarts (time weight, damage cost, expansion budget per goal conjunct): greedy search is
#: fast when its heuristic fits and lost when it does not; another weighting often fits. Budgets
#: count expansions, not seconds, so a run is the same on any machine. The last is unbounded.
SCHEDULE = ((None, 2.0, 20), (None, 5.0, 40), (0.3, 2.0, 40), (1.0, 2.0, 80), (0.03, 2.0, 160),
            (None, 2.0, None))


def _plan(
    task: Task, limits: Limits, stats: dict[str, Any], options: dict[str, Any],
    running: list[Search],
) -> PlanResult:
    t = time.perf_counter()
    ct = compile_task(task)
    kernel = Kernel(ct)
    stats["compile_s"] = time.perf_counter() - t
    reason = prove_unsolvable(task)
    if reason is not None:
        return PlanResult(PlanStatus.UNSOLVABLE_PROVEN, message=reason)
    config = SearchConfig(
        epsilon=float(options.get("epsilon", 0.001)),
        goal_margin=float(options.get("goal_margin", 0.01)),
        value_precision=int(options.get("value_precision", 6)),
    )
    checked: dict[int, tuple[Plan, Any]] = {}

    def accept(outcome: SearchOutcome) -> bool:
        """A goal node counts only if the validator agrees (else: a bug, counted, searched on)."""
        found = extract_plan(ct, outcome)
        if not options.get("validate", True):
            checked[0] = (found, None)
            return True
        report = _validate(task, found, stats, limits)
        if report.valid:
            checked[0] = (found, report.trajectory)
            return True
        stats.setdefault("rejected_reasons", []).append(report.reason)
        return False

    default_weight = float(options.get("time_weight", 0.1))
    t = time.perf_counter()
    heuristic_s = 0.0
    outcome = None
    try:
        for attempt, (weight, damage, per_goal) in enumerate(SCHEDULE, 1):
            heur = RateHeuristic(
                ct, HeuristicConfig(time_weight=weight or default_weight, damage_cost=damage),
                kernel.active)
            budget = float("inf") if per_goal is None else per_goal * max(5, len(heur.groups))
            search = Search(ct, kernel, heur, config, limits.check, accept)
            stats["attempts"] = attempt
            running[:] = [search]
            try:
                outcome = search.run(initial_node(ct, kernel), budget)
            finally:
                heuristic_s += heur.seconds
                running.clear()
                for k, v in search.stats.items():
                    stats[k] = stats.get(k, 0) + v
            if outcome.goal is not None or outcome.exhausted:
                break
    finally:
        stats.update(kernel.counters)
        stats["search_s"] = time.perf_counter() - t - stats.get("validate_s", 0.0)
        stats["heuristic_s"] = heuristic_s
    assert outcome is not None
    if outcome.goal is None:
        return PlanResult(PlanStatus.NO_PLAN, message="search space exhausted without a plan "
                          "(not a proof: waits stop only at critical times)")
    found, trajectory = checked[0]
    if options.get("improve", True):
        found, trajectory = _improve(task, ct, kernel, config, limits, found, trajectory, stats,
                                     options)
    stats["plan_length"] = len(found.actions)
    stats["makespan"] = found.makespan
    stats["validated"] = bool(options.get("validate", True))
    if trajectory is not None:
        stats["margins"] = plan_margins(task, found, trajectory, config.event_gap)
    return PlanResult(PlanStatus.SOLVED, found, trajectory)


#: A goal that holds by less than this at the plan's end [units of its values] has no margin.
GOAL_MARGIN_MIN = 1e-3


def plan_margins(task: Task, found: Plan, trajectory: Any, event_gap: float) -> dict[str, Any]:
    """How robust a validated plan is: ``event_gap_s``, the closest an action comes to an event
    [s] (None without events); ``goal_margin``, how far the goal is from failing at the end
    (in its values' units, e.g. deg); ``ok`` when both are at least ``event_gap`` and
    ``GOAL_MARGIN_MIN``; otherwise ``note`` says why (e.g. a goal window narrower than the
    margin, or an action the semantics ties to an event)."""
    from artiplan.semantics.walks import robustness

    times = [a.time for a in found.actions]
    gaps = [abs(a - e.time) for a in times for e in trajectory.events]
    gap = min(gaps) if gaps else None
    final = trajectory.final_state
    margin = robustness(task.goal, final.facts, final.values) if final is not None else None
    notes = []
    if gap is not None and gap < event_gap - 1e-9:
        notes.append(f"an action {gap:.6f} s from an event (wanted {event_gap:g} s)")
    if margin is not None and margin < GOAL_MARGIN_MIN:
        notes.append(f"the goal holds by only {margin:.2g} at the end")
    out: dict[str, Any] = {
        "event_gap_s": None if gap is None else round(gap, 6),
        "goal_margin": None if margin is None or margin == float("inf") else round(margin, 6),
        "ok": not notes,
    }
    if notes:
        out["note"] = "; ".join(notes)
    return out


def _improve(
    task: Task, ct: CompiledTask, kernel: Kernel, config: SearchConfig, limits: Limits,
    first: Plan, trajectory: Any, stats: dict[str, Any], options: dict[str, Any],
) -> tuple[Plan, Any]:
    """The anytime phase (:mod:`artiplan.search.improve`): a better validated plan, or ``first``."""

    validate_before = stats.get("validate_s", 0.0)  # the first plan's validation [s]

    def check(found: Plan) -> Any:
        if not options.get("validate", True):
            return None
        left = limits.remaining()
        if left is not None and left < 2.0 * validate_before:
            # validating might overrun the time limit: keep the first plan, validated already
            return SimpleNamespace(valid=False, reason="no time left to validate", trajectory=None)
        return _validate(task, found, stats, limits)

    t = time.perf_counter()
    best, report, extra = improve(ct, kernel, config, limits, first, int(stats.get("expanded", 0)),
                                  lambda outcome: extract_plan(ct, outcome), check)
    stats.update(extra)
    stats["improve_s"] = time.perf_counter() - t - (stats.get("validate_s", 0.0) - validate_before)
    stats["first_makespan"] = first.makespan
    stats["first_length"] = len(first.actions)
    if best is first:
        return first, trajectory
    return best, None if report is None else report.trajectory


def _validate(task: Task, found: Plan, stats: dict[str, Any], limits: Limits) -> Any:
    """The validator's report on a plan found; events enabled in the initial state (which VAL
    refuses, whatever the plan) are accepted here and named in ``stats``."""
    from artiplan.semantics import validate
    from artiplan.semantics.validator import enabled_initial_events

    t = time.perf_counter()
    if "initial_events" not in stats:
        stats["initial_events"] = [e.signature for e in enabled_initial_events(task)]
    report = validate(task, found, check=limits.check, initial_events=True)
    stats["validate_s"] = stats.get("validate_s", 0.0) + time.perf_counter() - t
    return report


def extract_plan(ct: CompiledTask, outcome: SearchOutcome) -> Plan:
    """The timed plan (actions and predicted events) leading to the goal node."""
    assert outcome.goal is not None
    path = []
    i = outcome.goal
    while i >= 0:
        path.append(outcome.nodes[i])
        i = outcome.nodes[i].parent
    path.reverse()
    actions: list[TimedAction] = []
    events: list[TimedEvent] = []
    for node in path:
        for k, (t, e) in enumerate(node.events):
            ev = ct.events[e]
            after = node.op[0] == "a" and k >= node.after
            events.append(TimedEvent(round(t, 6), ev.name, ev.args, after_actions=after))
        if node.op[0] == "a":
            a = ct.actions[node.op[1]]
            actions.append(TimedAction(round(node.time, 6), a.name, a.args))
    if outcome.closing is not None:
        t, i = outcome.closing
        a = ct.actions[i]
        actions.append(TimedAction(round(t, 6), a.name, a.args))
    return Plan(tuple(actions), tuple(events))
