"""artiplan's planner: ``plan(domain, problem) -> PlanResult``.

One planning call reads forward, each phase timed in :class:`~artiplan.semantics.results.PlanStats`:

    parse + ground (pddl) -> compile (semantics.compiled) -> prove unsolvable? (proofs)
    -> search (engine, on the kernel) -> extract the timed plan -> validate (semantics)
    -> improve (a bounded search for a better plan, validated the same way)

A plan the validator rejects is never returned as solved: the search goes on (counted as
``rejected``), and a limit or an exhausted search reports why.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator

from artiplan.errors import InvalidPlanError, UsageError
from artiplan.pddl.task import Atom, Condition, Effect, Task
from artiplan.records import dataclass, names, replace
from artiplan.search.engine import Search, SearchConfig, SearchOutcome, Successors, initial_node
from artiplan.search.heuristic import Heuristic, HeuristicConfig, RateHeuristic
from artiplan.search.improve import improve
from artiplan.search.limits import LimitReached, Limits
from artiplan.search.ops import Apply
from artiplan.search.proofs import prove_unsolvable
from artiplan.semantics.compiled import CompiledTask, compile_task
from artiplan.semantics.kernel import Kernel
from artiplan.semantics.plan import Plan, TimedAction, TimedEvent, fold_durative
from artiplan.semantics.results import PlanResult, PlanStats, PlanStatus, margins_of
from artiplan.semantics.validator import ValidationReport, enabled_initial_events, validate
from artiplan.semantics.walks import condition_parts, conjuncts, linear_difference
from artiplan.tolerances import VAL_EVENT_WINDOW, VAL_TIME_TOLERANCE

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from pathlib import Path
    from typing import Any

__all__ = ["OPTIONS", "PlanResult", "PlanStats", "PlanStatus", "PlannerConfig", "plan",
           "plan_task"]

#: ``heuristic(task, config, active)``: a :class:`Heuristic` for a compiled task; ``active``
#: tells which processes run in a state.
HeuristicFactory = Callable[[CompiledTask, HeuristicConfig, Callable[[int, tuple[float, ...]],
                                                                     tuple[int, ...]]], Heuristic]


@dataclass(frozen=True)
class PlannerConfig:
    """Settings of artiplan's planner.

    Attributes:
        epsilon: Separation [s] of actions meant one after the other (> VAL's tolerance).
        time_weight: Heuristic cost of one second of plan, in actions [1/s].
        goal_margin: Time [s] a goal wait runs on past the goal boundary while the goal keeps
            holding (the plan's end sees the goal with a margin).
        margin_per_event: The goal margin grows by this [s] per event before the goal wait
            (up to ``SearchConfig.max_goal_margin``): VAL's event timing errors add up over
            long cascades.
        event_gap: No action closer than this [s] to an event (1.5 x VAL's event window).
        value_precision: Decimals of values in duplicate detection.
        validate: Check every plan with the validator before returning it.
        improve: Search on for a better plan within an expansion budget.
        separate: Shift the plan's tail by a few ms where its timing makes two objects cross
            a boundary at one instant, which stock VAL mis-handles (:mod:`separate`).
        heuristic: Builds the search's heuristic (another one plugs in here).
    """

    epsilon: float = VAL_TIME_TOLERANCE
    time_weight: float = 0.1
    goal_margin: float = 0.01
    margin_per_event: float = 0.0002
    event_gap: float = 1.5 * VAL_EVENT_WINDOW
    value_precision: int = 6
    validate: bool = True
    improve: bool = True
    separate: bool = True
    heuristic: HeuristicFactory = RateHeuristic

    @classmethod
    def of(cls, **options: Any) -> PlannerConfig:
        """A config from keyword options (``plan(..., epsilon=0.002)``).

        Raises:
            UsageError: an unknown option (the message lists the valid ones).
        """
        unknown = set(options) - set(OPTIONS)
        if unknown:
            raise UsageError(f"unknown planner option(s) {sorted(unknown)}; valid: "
                             f"{sorted(OPTIONS)}")
        return cls(**options)

    def search(self) -> SearchConfig:
        return SearchConfig(epsilon=self.epsilon, goal_margin=self.goal_margin,
                            margin_per_event=self.margin_per_event,
                            value_precision=self.value_precision, event_gap=self.event_gap)


#: The planner's keyword options (name -> the field's type), for scripts and front ends.
OPTIONS: dict[str, type] = {name: type(getattr(PlannerConfig, name))
                            for name in names(PlannerConfig) if name != "heuristic"}

#: ``on_progress(elapsed [s], statistics so far)``: called every 2 s of a long planning call.
Progress = Callable[[float, PlanStats], None]

@dataclass(frozen=True)
class Attempt:
    """One greedy search of the restart schedule.

    Attributes:
        numeric: Use the general numeric relaxation (:mod:`artiplan.search.numeric`) with free
            waits, instead of the configured (rate) heuristic with critical-time waits.
        time_weight: The heuristic's cost of a second [actions/s] (None: the config's).
        damage: Cost of undoing a goal already reached (the rate heuristic's).
        per_goal: Expansion budget per goal conjunct (times at least 5); None: unbounded.
        delta: Step of the free waits [s] (numeric attempts).
    """

    numeric: bool
    time_weight: float | None
    damage: float
    per_goal: int | None
    delta: float | None = None


#: Restarts: greedy search is fast when its heuristic fits and lost when it does not; another
#: weighting often fits. The paper's encodings are solved by the first attempts (rate heuristic,
#: waits to critical times); other domains need choices of time no condition marks (free waits
#: on a grid of ``delta`` seconds, refined round by round) and a relaxation that reads numeric
#: preconditions. Budgets count expansions, not seconds, so a run is the same on any machine.
FIRST = (Attempt(False, None, 2.0, 20), Attempt(False, None, 5.0, 40),
         Attempt(True, None, 2.0, 100, 1.0), Attempt(False, 0.3, 2.0, 40),
         Attempt(False, 1.0, 2.0, 80), Attempt(True, None, 2.0, 200, 0.5),
         Attempt(False, 0.03, 2.0, 160))
#: Free-wait steps [s] of the rounds after ``FIRST`` (each round doubles the budgets); the
#: finest one is searched without a budget.
DELTAS = (1.0, 0.5, 0.25, 0.1, 0.05)
#: Most seconds the separation of coincident crossings may take (see PlannerConfig.separate).
SEPARATE_S = 10.0


def goal_behind_comparisons(task: Task) -> bool:
    """True if a goal fact not true initially is added only by actions, each of which needs a
    nonlinear comparison to hold (``capture`` when the squared distance is below a radius).
    The rate heuristic reads a linear comparison's rate of change, not a nonlinear one's:
    such a goal looks one action away from every state, and the numeric relaxation, which
    reads it, is the one to try first."""
    def nonlinear(cond: Condition) -> bool:
        return any(linear_difference(c) is None for c in condition_parts(cond)[2])

    goal_facts = {c.fact for c in conjuncts(task.goal) if isinstance(c, Atom)} - task.init_facts
    if not goal_facts:
        return False
    adders: dict[int, list[bool]] = {f: [] for f in goal_facts}  # fact -> gated, per adder

    def note(effect: Effect, gated: bool, is_action: bool) -> None:
        for f in effect.add:
            if f in adders:
                adders[f].append(gated and is_action)
        for ce in effect.conditional:
            note(ce.effect, gated or nonlinear(ce.condition), is_action)

    for op in task.actions:
        note(op.effect, nonlinear(op.precondition), True)
    for ev in task.events:
        note(ev.effect, False, False)
    for pr in task.processes:
        for f in pr.discrete.add:
            if f in adders:
                adders[f].append(False)
    return any(gates and all(gates) for gates in adders.values())


def schedule(numeric_first: bool = False) -> Iterator[Attempt]:
    """The attempts in order: ``FIRST``, then rounds of (numeric, rate) with doubled budgets
    and finer steps, ending with an unbounded numeric search on the finest step.

    ``numeric_first``: ``FIRST``'s numeric attempts go first (a task whose goal needs a
    position and its speed steered together, :mod:`artiplan.search.motion`, which the rate
    heuristic cannot read)."""
    if numeric_first:
        yield from (a for a in FIRST if a.numeric)
        yield from (a for a in FIRST if not a.numeric)
    else:
        yield from FIRST
    for r, delta in enumerate(DELTAS):
        last = r == len(DELTAS) - 1
        yield Attempt(True, None, 2.0, None if last else 400 * 2 ** r, delta)
        if not last:
            yield Attempt(False, None, 2.0, 320 * 2 ** r)


def plan(
    domain: str | Path, problem: str | Path, *, time_limit: float | None = None,
    memory_limit: float | None = None, on_progress: Progress | None = None,
    config: PlannerConfig | None = None, **options: Any,
) -> PlanResult:
    """Plan for a PDDL+ domain and problem (paths or PDDL text); see :func:`plan_task`.

    ``time_limit`` [s] covers parsing and grounding too; ``memory_limit`` [MB]. Options are
    :class:`PlannerConfig`'s fields (or pass ``config``).
    """
    from artiplan.pddl import load_task

    t0 = time.perf_counter()
    # Grounding a long chain takes seconds: it obeys the limit and shows progress too.
    check = None
    if time_limit is not None or on_progress is not None:
        check = Limits(time_limit, on_progress=None if on_progress is None else
                       lambda elapsed: on_progress(elapsed, PlanStats())).check
    try:
        task = load_task(domain, problem, check)
    except LimitReached as exc:
        result = PlanResult(PlanStatus.TIMEOUT, message=f"{exc} (while grounding)")
        result.stats.total_s = time.perf_counter() - t0
        return result
    load_s = time.perf_counter() - t0
    remaining = None if time_limit is None else max(0.0, time_limit - load_s)
    result = plan_task(task, time_limit=remaining, memory_limit=memory_limit,
                       on_progress=on_progress, config=config, **options)
    result.stats.ground_s = task.stats.seconds
    result.stats.parse_s = max(0.0, load_s - task.stats.seconds)
    result.stats.total_s += load_s
    return result


def plan_task(
    task: Task, *, time_limit: float | None = None, memory_limit: float | None = None,
    on_progress: Progress | None = None, config: PlannerConfig | None = None, **options: Any,
) -> PlanResult:
    """Plan for a grounded task under the limits (``time_limit`` [s], ``memory_limit`` [MB]).

    The limits cover the validation of the plans found too (it can take seconds on long
    chains); ``on_progress`` is called about every 2 s with the counters so far.
    """
    if config is None or options:
        config = replace(config, **options) if config else PlannerConfig.of(**options)
    run = _Planning(task, config, time_limit, memory_limit, on_progress)
    t0 = time.perf_counter()
    try:
        result = run.solve()
    except LimitReached as exc:
        status = PlanStatus.TIMEOUT if exc.kind == "time" else PlanStatus.MEMOUT
        result = PlanResult(status, message=str(exc))
    except MemoryError:
        result = PlanResult(PlanStatus.MEMOUT, message="out of memory (MemoryError)")
    except InvalidPlanError as exc:
        result = PlanResult(PlanStatus.ERROR, message=str(exc))
    result.stats = run.stats
    run.stats.total_s = time.perf_counter() - t0
    return result


class _Planning:
    """One planning call: the phases in order, the statistics, the limits."""

    def __init__(self, task: Task, config: PlannerConfig, time_limit: float | None,
                 memory_limit: float | None, on_progress: Progress | None) -> None:
        self.task, self.config = task, config
        self.stats = PlanStats()
        self.running: Search | None = None  # the search under way (for progress lines)
        self.on_progress = on_progress
        self.limits = Limits(time_limit, memory_limit,
                             on_progress=self._report if on_progress else None)
        self.best: tuple[Plan, ValidationReport | None] | None = None
        self.winner = FIRST[0]  # the attempt that found the first plan
        self.winner_expanded = 0  # and its expansions (they set the improvement budget)
        self.rate: RateHeuristic | None = None  # the rate heuristic, once built
        # successors of the rate-heuristic attempts (one search config, one set of goal
        # groups): each later attempt and the improvement phase start from the same root
        self.memo: Successors | None = {} if config.heuristic is RateHeuristic else None

    def _report(self, elapsed: float) -> None:
        assert self.on_progress is not None
        now = replace(self.stats)
        if self.running is not None:
            now.add(self.running.stats)
        self.on_progress(elapsed, now)

    def solve(self) -> PlanResult:
        # The phases before the search do not check the limits inside: check between them.
        self.limits.check()
        t = time.perf_counter()
        self.ct = compile_task(self.task, strict=True)
        self.kernel = Kernel(self.ct)
        self.stats.compile_s = time.perf_counter() - t
        self.limits.check()
        reason = prove_unsolvable(self.task)
        if reason is not None:
            return PlanResult(PlanStatus.UNSOLVABLE_PROVEN, message=reason)
        self.limits.check()
        outcome = self._search()
        if (outcome.goal is None and not outcome.repaired) or self.best is None:
            return PlanResult(PlanStatus.NO_PLAN, message="search space exhausted without a "
                              "plan (not a proof: waits stop only at critical times)")
        if self.config.improve:
            self._improve()
        if self.config.validate and self.config.separate:
            self._separate()
        found, report = self.best
        stats = self.stats
        stats.plan_length, stats.makespan = len(found.actions), found.makespan
        stats.validated = self.config.validate
        trajectory = report.trajectory if report is not None else None
        if trajectory is not None:
            stats.margins = margins_of(self.task, found, trajectory, self.config.event_gap)
        return PlanResult(PlanStatus.SOLVED, found, trajectory)

    def _search(self) -> SearchOutcome:
        """Greedy searches with restarts (:func:`schedule`) until a validated plan."""
        stats = self.stats
        t = time.perf_counter()
        outcome: SearchOutcome | None = None
        exhausted: set[tuple[bool, float | None]] = set()
        try:
            from artiplan.search.motion import find_controls, find_motions

            numeric_first = bool(find_motions(self.task, find_controls(self.task))) or \
                goal_behind_comparisons(self.task)
            for n, attempt in enumerate(schedule(numeric_first), 1):
                kind = (attempt.numeric, attempt.delta)
                if kind in exhausted:
                    continue  # the same operators searched their whole space already
                heur, search_config = self._attempt(attempt)
                self.limits.check()
                budget = float("inf") if attempt.per_goal is None else \
                    attempt.per_goal * max(5, len(heur.groups))
                search = Search(self.ct, self.kernel, heur, search_config, self.limits.check,
                                self._accept, repair=self._repair if attempt.numeric else None,
                                successors=None if attempt.numeric else self.memo)
                stats.attempts = n
                self.running = search
                try:
                    root = initial_node(self.ct, self.kernel)
                    self.limits.check()
                    outcome = search.run(root, budget)
                finally:
                    self.running = None
                    stats.heuristic_s += heur.seconds
                    stats.add(search.stats)
                if outcome.goal is not None or outcome.repaired:
                    self.winner = attempt
                    self.winner_expanded = int(search.stats["expanded"])
                    break
                if outcome.exhausted:
                    exhausted.add(kind)
                    if not attempt.numeric:
                        exhausted.add((False, None))
                    if attempt.numeric and attempt.delta == DELTAS[-1]:
                        break
        finally:
            stats.add(self.kernel.counters)
            self.kernel.counters = dict.fromkeys(self.kernel.counters, 0)
            stats.search_s = time.perf_counter() - t - stats.validate_s
        assert outcome is not None
        return outcome

    def _attempt(self, attempt: Attempt,
                 time_weight: float | None = None) -> tuple[Heuristic, SearchConfig]:
        """The heuristic and search settings of one attempt."""
        config = self.config
        weight = time_weight or attempt.time_weight or config.time_weight
        hc = HeuristicConfig(time_weight=weight, damage_cost=attempt.damage)
        if not attempt.numeric:
            return self._heuristic(hc), self._search_config(attempt)
        from artiplan.search.numeric import NumericHeuristic  # here: general domains only

        return NumericHeuristic(self.ct, hc, self.kernel.active), self._search_config(attempt)

    def _search_config(self, attempt: Attempt) -> SearchConfig:
        """The search settings of one attempt (numeric ones: free waits, actions counted)."""
        if not attempt.numeric:
            return self.config.search()
        return replace(self.config.search(), delta=attempt.delta, before_events=True,
                       g_weight=1.0)

    def _heuristic(self, hc: HeuristicConfig) -> Heuristic:
        """The configured heuristic with weights ``hc``; the rate heuristic is built once and
        then reweighted (its setup reads the task only: restarts and the improvement's
        searches would build the same again)."""
        factory = self.config.heuristic
        if factory is not RateHeuristic:
            return factory(self.ct, hc, self.kernel.active)
        if self.rate is None:
            self.rate = RateHeuristic(self.ct, hc, self.kernel.active)
            return self.rate
        return self.rate.reweighted(hc)

    def _repair(self, actions: list[int], times: list[float]) -> bool:
        """A timing repair of a skeleton (:mod:`artiplan.search.timing`); True when the
        repaired plan is valid (it becomes the best plan)."""
        from artiplan.search.timing import Repair, repair_times  # here: general domains only

        t = time.perf_counter()
        settings = Repair(epsilon=self.config.epsilon, event_gap=self.config.event_gap)
        evals: list[int] = []
        try:
            fixed = repair_times(self.ct, self.kernel, actions, times, settings,
                                 self.limits.check, evals)
        finally:
            self.stats.repair_s += time.perf_counter() - t
            self.stats.repair_evals += sum(evals)
        if fixed is None:
            return False
        acts = self.ct.actions
        found = fold_durative(Plan(tuple(TimedAction(round(at, 6), acts[a].name, acts[a].args)
                                         for a, at in zip(actions, fixed, strict=True))),
                              self.task.durative)
        return self._keep(found, with_events=True)

    def _accept(self, outcome: SearchOutcome) -> bool:
        """A goal node counts only if the validator agrees (else: searched on, counted)."""
        return self._keep(extract_plan(self.ct, outcome))

    def _keep(self, found: Plan, with_events: bool = False) -> bool:
        """True, and ``found`` is the best plan, if the validator accepts it (or validation is
        off; ``with_events``: the plan takes the validator's events); else the reason counts."""
        if not self.config.validate:
            self.best = (found, None)
            return True
        report = self._validate(found)
        if report.valid:
            self.best = (replace(found, events=tuple(report.events)) if with_events else found,
                         report)
            return True
        self.stats.rejected_reasons.append(report.reason)
        return False

    def _validate(self, found: Plan) -> ValidationReport:
        """The validator's report; events enabled in the initial state (which VAL refuses,
        whatever the plan) are accepted here and named in the statistics."""
        t = time.perf_counter()
        if not self.stats.initial_events:
            self.stats.initial_events = [e.signature for e in enabled_initial_events(self.task)]
        report = validate(self.task, found, check=self.limits.check, initial_events=True)
        self.stats.validate_s += time.perf_counter() - t
        return report

    def _separate(self) -> None:
        """Pull apart crossings the plan's timing makes coincide, within at most half the time
        left (and :data:`SEPARATE_S` without a limit); the plan stays if none helps."""
        from artiplan.search.separate import separate

        assert self.best is not None
        found, report = self.best
        if report is None:
            return
        remaining = self.limits.remaining()
        budget = SEPARATE_S if remaining is None else min(SEPARATE_S, 0.5 * remaining)
        stop = time.monotonic() + budget
        t = time.perf_counter()
        try:
            better = separate(self.task, found, report, self.config.event_gap, self._validate,
                              lambda: time.monotonic() > stop)
        except LimitReached:
            better = None
        self.stats.separate_s = time.perf_counter() - t
        if better is not None:
            self.best = better
            self.stats.separated = True

    def _improve(self) -> None:
        """The anytime phase (:mod:`artiplan.search.improve`): a better validated plan."""
        assert self.best is not None
        first = self.best[0]
        validate_before = self.stats.validate_s  # the first plan's validation [s]

        def check(found: Plan) -> ValidationReport | None:
            if not self.config.validate:
                return None
            left = self.limits.remaining()
            if left is not None and left < 2.0 * validate_before:
                # validating might overrun the time limit: keep the first plan
                return ValidationReport(False, "no time left to validate")
            return self._validate(found)

        t = time.perf_counter()
        winner = self.winner

        def heuristic(ct: CompiledTask, hc: HeuristicConfig, active: Any) -> Heuristic:
            return self._attempt(replace(winner, damage=hc.damage_cost),
                                 hc.time_weight)[0]

        best, report = improve(self.ct, self.kernel, self._search_config(winner), self.limits,
                               first, self.stats, lambda outcome: extract_plan(self.ct, outcome),
                               check, heuristic=heuristic, expanded=self.winner_expanded,
                               successors=None if winner.numeric else self.memo)
        self.stats.add(self.kernel.counters)
        self.stats.improve_s = time.perf_counter() - t - (self.stats.validate_s - validate_before)
        self.stats.first_makespan, self.stats.first_length = first.makespan, len(first.actions)
        if best is not first:
            self.best = (best, report)


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
        by_action = isinstance(node.op, Apply)
        for k, (t, e) in enumerate(node.events):
            ev = ct.events[e]
            events.append(TimedEvent(round(t, 6), ev.name, ev.args,
                                     after_actions=by_action and k >= node.after))
        if isinstance(node.op, Apply):
            a = ct.actions[node.op.action]
            actions.append(TimedAction(round(node.time, 6), a.name, a.args))
    if outcome.closing is not None:
        t, i = outcome.closing
        a = ct.actions[i]
        actions.append(TimedAction(round(t, 6), a.name, a.args))
    return fold_durative(Plan(tuple(actions), tuple(events)), ct.task.durative)
