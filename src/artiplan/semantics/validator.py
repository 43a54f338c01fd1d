"""Simulating and validating timed plans with VAL's semantics: the kernel plus diagnostics.

What is checked, exactly (the kernel, :mod:`artiplan.semantics.kernel`, does the dynamics):

* Actions are grouped into happenings by their time rounded to 1e-6 s (plans carry 6 decimals)
  and applied in parallel: all preconditions read in the state just before the happening
  (after the events of that instant), then all effects together.
* Mutex: two actions of one happening that interfere make the plan invalid; so do two actions
  of different happenings less than ``tolerance`` apart (``|t1 - t2| < tolerance - 1e-9``; so
  0.001 apart with tolerance 0.001 is fine). Interfere: one writes a fact or fluent the other
  reads, or one adds what the other deletes, or both write one fluent (unless both only
  increase/decrease it).
* Time passes exactly between happenings; events fire at the exact earliest instant their
  precondition holds, before the actions of that instant; events cascade; an event triggered
  twice at one instant makes the plan invalid.
* Comparisons are read with the tolerances (VAL's: slack 1e-4 on every comparison) in
  preconditions, the goal, event triggers and conditions of conditional effects.
* The goal is checked once, in the state after the last happening (and its events).
* An initial state in which an event's precondition holds is refused (VAL: "Event
  preconditions are not permitted to be satisfied in the initial state"), unless the caller
  accepts it (``initial_events=True``: the events fire at time 0).
* An action the task does not know (or an event written as an action) is "bad operator".
* A durative action ``t: (N args) [d]`` is its compiled start at ``t`` and end at ``t + d``;
  invariants (global constraints, ``over all`` conditions) must hold on every stretch of time
  (kind ``invariant``), and ENHSP's global constraints in the initial state too.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Condition, GroundAction, Task
from artiplan.records import dataclass, field
from artiplan.semantics.cache import per_task
from artiplan.semantics.compiled import CompiledTask, Operator, compile_task
from artiplan.semantics.interference import interferes
from artiplan.semantics.kernel import Active, EventError, EventLog, InvariantError, Kernel, Segment
from artiplan.semantics.plan import Plan, TimedAction, TimedEvent, expand_durative
from artiplan.semantics.state import State
from artiplan.semantics.trajectory import Trajectory, TrajectoryRow
from artiplan.semantics.walks import fluent_values, format_condition, holds, unsatisfied_parts
from artiplan.tolerances import VAL, VAL_TIME_TOLERANCE, Tolerances


@dataclass
class ValidationReport:
    """The verdict on a plan.

    Attributes:
        valid: True when the plan is valid.
        reason: The first failure, one line ("" when valid).
        kind: ``precondition``, ``goal``, ``mutex``, ``bad-operator``, ``event``, ``error``
            (division by zero, Zeno behaviour) or "" when valid.
        happening: 1-based index of the failing happening (0: before the first one).
        time: Time [s] of the failure.
        condition: The failed condition as PDDL text.
        values: Value of every fluent the failed condition reads.
        line: Plan file line of the failing action, when known.
        trajectory: Everything simulated up to the failure (or to the end).
        events: The events fired, with exact times.
    """

    valid: bool
    reason: str = ""
    kind: str = ""
    happening: int | None = None
    time: float | None = None
    condition: str | None = None
    values: dict[str, float] = field(default_factory=dict)
    line: int | None = None
    trajectory: Trajectory | None = None
    events: list[TimedEvent] = field(default_factory=list)

    def summary(self) -> str:
        """A few human lines: the verdict and, if invalid, where and why."""
        if self.valid:
            return "Plan valid"
        lines = [f"Plan invalid: {self.reason}"]
        if self.condition:
            lines.append(f"  condition: {self.condition}")
        for name, v in self.values.items():
            lines.append(f"  {name} = {v:.6f}")
        return "\n".join(lines)


def _key(signature: str) -> str:
    return " ".join(signature.lower().replace("(", " ").replace(")", " ").split())


def resolve(task: Task, action: TimedAction) -> GroundAction | None:
    """The ground action a plan line names (case-insensitive), or None."""
    index = _action_index(task).get(_key(action.signature))
    return None if index is None else task.actions[index]


def _action_index(task: Task) -> dict[str, int]:
    return per_task(task, "action-index",
                    lambda: {_key(a.signature): i for i, a in enumerate(task.actions)})


def _groups(plan: Plan) -> list[tuple[float, list[TimedAction]]]:
    out: dict[float, list[TimedAction]] = {}
    for a in sorted(plan.actions, key=lambda a: a.time):
        out.setdefault(round(a.time, 6), []).append(a)
    return sorted(out.items())


class _Failure(Exception):
    def __init__(self, report: ValidationReport) -> None:
        self.report = report


def _fail(kind: str, reason: str, happening: int, time: float, **kw: object) -> _Failure:
    return _Failure(ValidationReport(False, reason, kind, happening, time, **kw))  # type: ignore[arg-type]


@dataclass
class _Run:
    """One simulation: the kernel, the trajectory being built and the options."""

    ct: CompiledTask
    kernel: Kernel
    traj: Trajectory
    tolerance: float
    check: bool
    tick: Callable[[], None] | None

    @property
    def task(self) -> Task:
        return self.ct.task

    def record(self, log: EventLog, values_after: Callable[[int], tuple[float, ...]]
               | tuple[float, ...], after_actions: bool = False) -> None:
        """The events of ``log`` into the trajectory; rows carry the values after each
        instant's cascade (``values_after(k)`` for the k-th event, or one tuple for all)."""
        events = self.ct.events
        for k, (t, i) in enumerate(log):
            ev = events[i]
            values = values_after if isinstance(values_after, tuple) else values_after(k)
            self.traj.events.append(TimedEvent(t, ev.name, ev.args, after_actions=after_actions))
            self.traj.rows.append(TrajectoryRow(t, ev.signature, values, "event"))

    def advance(self, t: float, facts: int, values: tuple[float, ...], until: float,
                active: Active, index: int) -> tuple[int, tuple[float, ...], Active]:
        log: EventLog = []
        segments: list[Segment] = []
        try:
            facts, values, active = self.kernel.advance(t, facts, values, until, log, active,
                                                        segments)
        except EventError as exc:
            raise _fail("event", str(exc), index, exc.time) from None
        finally:
            self.traj.segments.extend(segments)
        self.record(log, lambda k: _values_at(segments, log[k][0], values))
        return facts, values, active


def _values_at(segments: list[Segment], t: float, final: tuple[float, ...]) -> tuple[float, ...]:
    """Values just after the instant ``t`` (the start of the segment that begins there)."""
    for seg in segments:
        if seg.t0 >= t - 1e-12:
            return seg.start
    return final


def _condition_failure(run: _Run, cond: Condition, facts: int, values: Sequence[float], t: float,
                       what: str, index: int, line: int | None) -> _Failure:
    tol = run.ct.tol
    parts = unsatisfied_parts(cond, facts, values, tol)
    text = " ".join(format_condition(p, run.task) for p in parts)
    named: dict[str, float] = {}
    for p in parts:
        named.update(fluent_values(p, run.task, values))
    undefined = [n for n, v in named.items() if v != v]  # nan: never given a value
    note = f" (undefined: {', '.join(undefined)})" if undefined else ""
    return _fail("goal" if index < 0 else "precondition", f"{what} at time {t:.6f}: {text} is "
                 f"false{note}", max(index, 0), t, condition=text, values=named, line=line)


def _check_happening(
    run: _Run, index: int, t: float, facts: int, values: tuple[float, ...],
    acts: Sequence[tuple[TimedAction, Operator]],
    previous: Sequence[tuple[TimedAction, Operator]],
) -> None:
    for i, (ta, oa) in enumerate(acts):
        for tb, ob in [*acts[i + 1:], *previous]:
            if interferes(oa.source, ob.source):
                raise _fail(
                    "mutex", f"mutex violation: {oa.signature} at {ta.time:.6f} and "
                    f"{ob.signature} at {tb.time:.6f} interfere (separate them by more than "
                    f"{run.tolerance} s)", index, ta.time, line=ta.line)
    for ta, op in acts:
        if facts & op.forb or op.req & ~facts or not op.pre(facts, values):
            what = f"precondition of {op.signature} (happening {index})"
            raise _condition_failure(run, op.source.precondition, facts, values, t, what, index,
                                     ta.line)


def _resolve_all(run: _Run, groups: list[tuple[float, list[TimedAction]]]
                 ) -> list[list[tuple[TimedAction, Operator]]]:
    """The compiled action of every plan line, per happening; "bad operator" if unknown."""
    table = _action_index(run.task)
    resolved = []
    for index, (t, timed) in enumerate(groups, 1):
        pairs = []
        for ta in timed:
            k = table.get(_key(ta.signature))
            if k is None:
                where = f" (plan line {ta.line})" if ta.line else ""
                raise _fail("bad-operator", f"bad operator {ta.signature} at time {t:.6f}{where}",
                            index, t, line=ta.line)
            pairs.append((ta, run.ct.actions[k]))
        resolved.append(pairs)
    return resolved


def enabled_initial_events(task: Task, tol: Tolerances = VAL) -> list[GroundAction]:
    """The events whose precondition holds in the initial state (read as VAL reads it)."""
    ct = compile_task(task, tol)
    return [e.source for e in ct.events
            if not ct.init_facts & e.forb and holds(e.source.precondition, ct.init_facts,
                                                     ct.init_values, tol)]


def run_plan(
    task: Task,
    plan: Plan,
    *,
    tol: Tolerances = VAL,
    tolerance: float = VAL_TIME_TOLERANCE,
    check: bool = True,
    extend: float = 0.0,
    tick: Callable[[], None] | None = None,
    initial_events: bool = False,
) -> ValidationReport:
    """Simulate ``plan``; with ``check`` also judge it (module docstring).

    ``extend`` [s]: keep simulating (events included) that long after the plan's end, so the
    trajectory predicts what happens next; the goal is still checked at the plan's end.
    ``tick()`` is called before every happening; what it raises (a caller's time limit) ends
    the run. ``initial_events``: accept an initial state in which events are enabled.
    """
    ct = compile_task(task, tol)
    run = _Run(ct, Kernel(ct), Trajectory(task.fluents), tolerance, check, tick)
    try:
        plan = expand_durative(plan, task.durative)
    except ValueError as exc:
        return ValidationReport(False, str(exc), "bad-operator", 0, 0.0)
    traj = run.traj
    traj.rows.append(TrajectoryRow(0.0, "init", ct.init_values, "init"))
    report = ValidationReport(True)
    try:
        if check and not initial_events:
            enabled = enabled_initial_events(task, tol)
            if enabled:
                names = ", ".join(e.signature for e in enabled[:3])
                raise _fail("event", f"event preconditions hold in the initial state ({names}"
                            f"{' ...' if len(enabled) > 3 else ''}): VAL does not allow an "
                            "event at time 0", 0, 0.0,
                            condition=format_condition(enabled[0].precondition, task))
        t, facts, values, active = _run_happenings(run, plan)
        traj.final_state = State(t, facts, values)
        if check and not ct.goal(facts, values):
            n = len(_groups(plan))
            where = f"the plan's end ({t:.6f})" if plan.end else f"the last happening ({n})"
            raise _condition_failure(run, task.goal, facts, values, t, f"goal at {where}", -1,
                                     None)
        if extend > 0:
            after = len(_groups(plan)) + 1
            facts, values, active = run.advance(t, facts, values, t + extend, active, after)
            t += extend
        traj.segments.append(Segment(t, float("inf"), values, run.kernel.flow_of(active, values)))
        traj.end = t
    except _Failure as f:
        report = f.report
    except InvariantError as exc:
        report = ValidationReport(False, str(exc), "invariant", time=exc.time,
                                  condition=format_condition(exc.condition, task))
    except (InvalidPlanError, ZeroDivisionError) as exc:  # Zeno, unsettled events, x / 0
        at = traj.rows[-1].time if traj.rows else 0.0
        what = "division by zero" if isinstance(exc, ZeroDivisionError) else str(exc)
        report = ValidationReport(False, f"{what} (after time {at:.6f})", "error", time=at)
    report.trajectory, report.events = traj, traj.events  # everything up to a failure too
    return report


def _run_happenings(run: _Run, plan: Plan) -> tuple[float, int, tuple[float, ...], Active]:
    """Every happening in turn; returns the time, facts, values and active processes after
    the last one (or at the plan's explicit end)."""
    ct, kernel = run.ct, run.kernel
    groups = _groups(plan)
    resolved = _resolve_all(run, groups)
    log: EventLog = []
    try:
        facts, values, active = kernel.settle(0.0, ct.init_facts, ct.init_values, log)
    except EventError as exc:
        raise _fail("event", str(exc), 0, exc.time) from None
    run.record(log, values)
    t = 0.0
    recent: list[tuple[float, list[tuple[TimedAction, Operator]]]] = []
    for index, ((at, _), acts) in enumerate(zip(groups, resolved, strict=True), 1):
        if run.tick is not None:
            run.tick()
        facts, values, active = run.advance(t, facts, values, at, active, index)
        t = at
        if run.check:
            near = [p for tp, g in recent if t - tp < run.tolerance - 1e-9 for p in g]
            _check_happening(run, index, t, facts, values, acts, near)
        facts, values = kernel.apply([op for _, op in acts], facts, values)
        run.traj.rows.append(TrajectoryRow(t, " ".join(op.signature for _, op in acts), values))
        log = []
        try:
            facts, values, active = kernel.settle(t, facts, values, log)
        except EventError as exc:
            raise _fail("event", str(exc), index, exc.time) from None
        run.record(log, values, after_actions=True)
        recent = [*recent[-8:], (t, acts)]
    if plan.end is not None and plan.end > t + 1e-9:
        facts, values, active = run.advance(t, facts, values, plan.end, active, len(groups) + 1)
        run.traj.rows.append(TrajectoryRow(plan.end, "end", values))
        t = plan.end
    return t, facts, values, active


def validate(
    task: Task,
    plan: Plan,
    tolerance: float = VAL_TIME_TOLERANCE,
    *,
    tol: Tolerances = VAL,
    check: Callable[[], None] | None = None,
    initial_events: bool = False,
) -> ValidationReport:
    """Validate ``plan`` against ``task`` with VAL's semantics (module docstring).

    ``check()``, if given, is called before every happening (a caller's time limit: what it
    raises propagates). ``initial_events``: accept events enabled in the initial state."""
    return run_plan(task, plan, tol=tol, tolerance=tolerance, check=True, tick=check,
                    initial_events=initial_events)


def simulate(
    task: Task,
    plan: Plan,
    sample_dt: float | None = None,
    *,
    extend: float = 0.0,
    tol: Tolerances = VAL,
) -> Trajectory:
    """The trajectory of ``plan`` (preconditions and goal not checked).

    ``sample_dt`` [s]: add sampled rows; ``extend`` [s]: simulate on after the plan's end.
    Raises InvalidPlanError for an action the task does not know or an event triggered twice.
    """
    report = run_plan(task, plan, tol=tol, check=False, extend=extend)
    if not report.valid:
        raise InvalidPlanError(report.reason)
    traj = report.trajectory
    assert traj is not None
    if sample_dt:
        end = traj.final_state.time + extend if traj.final_state is not None else None
        traj.add_samples(sample_dt, end)
    return traj
