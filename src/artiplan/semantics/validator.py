"""Simulating and validating timed plans with VAL's semantics (shared/docs/stack.md).

What is implemented, exactly:

* Actions are grouped into happenings by their time rounded to 1e-6 s (plans carry 6 decimals).
  Actions of one happening are applied in parallel (``happenings``): all preconditions read in
  the state just before it (after the events of that instant), then all effects together.
* Mutex: two actions of one happening that interfere make the plan invalid; so do two actions
  of different happenings less than ``tolerance`` apart (``|t1 - t2| < tolerance - 1e-9``; so
  0.001 apart with tolerance 0.001 is fine). Interfere = one writes a fact or fluent the other
  reads (precondition, effect condition, right-hand side), or one adds what the other deletes,
  or both write one fluent, unless both only increase/decrease it (commutative).
* Between happenings time passes exactly (``simulator.advance``): events fire at the exact
  earliest instant their precondition holds, before the actions of that instant; events cascade;
  an event triggered twice at one instant makes the plan invalid.
* Comparisons are read with :data:`VAL_TOLERANCES`: strict ones with VAL's slack 1e-4
  (``x > c`` iff ``x - c > -0.0001``), the others with 1e-9 rounding slack. This applies to
  preconditions, the goal and event triggers (so an event that puts a value exactly on another
  event's strict boundary bounces, as in VAL).
* The goal is checked once, in the state after the last happening (and its events).
* An initial state in which an event's precondition holds is refused (VAL: "Event
  preconditions are not permitted to be satisfied in the initial state"), unless the caller
  accepts it (``initial_events=True``: the events fire at time 0).
* An action the task does not know (or an event written as an action) is "bad operator".
* Undefined fluents read by a failed condition are reported as ``nan``.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Condition, GroundAction, Task
from artiplan.semantics.cache import per_task
from artiplan.semantics.dynamics import DEFAULT_FLOW, Flow, FlowConfig
from artiplan.semantics.expressions import (
    VAL_TOLERANCES,
    CondFn,
    Tolerances,
    compile_condition,
    fluent_values,
    format_condition,
    holds_values,
    unsatisfied_parts,
)
from artiplan.semantics.happenings import EventError, apply_actions, fire_events
from artiplan.semantics.interference import interferes
from artiplan.semantics.plan import Plan, TimedAction, TimedEvent
from artiplan.semantics.simulator import Segment, advance
from artiplan.semantics.state import State, initial_state
from artiplan.semantics.trajectory import Trajectory, TrajectoryRow


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


def _action_table(task: Task) -> dict[str, GroundAction]:
    return {_key(a.signature): a for a in task.actions}


def resolve(task: Task, action: TimedAction) -> GroundAction | None:
    """The ground action a plan line names (case-insensitive), or None."""
    table = per_task(task, "action-table", lambda: _action_table(task))
    return table.get(_key(action.signature))


def _groups(plan: Plan) -> list[tuple[float, list[TimedAction]]]:
    out: dict[float, list[TimedAction]] = {}
    for a in sorted(plan.actions, key=lambda a: a.time):
        out.setdefault(round(a.time, 6), []).append(a)
    return sorted(out.items())


class _Failure(Exception):
    def __init__(self, report: ValidationReport) -> None:
        self.report = report


def _fail(kind: str, reason: str, happening: int, time: float, **kw: object) -> _Failure:
    return _Failure(
        ValidationReport(False, reason, kind, happening, time, **kw)  # type: ignore[arg-type]
    )


@dataclass(frozen=True)
class _Run:
    task: Task
    tol: Tolerances
    config: FlowConfig
    tolerance: float
    check: bool
    tick: Callable[[], None] | None = None


def _condition_failure(
    run: _Run, cond: Condition, state: State, what: str, index: int, line: int | None
) -> _Failure:
    parts = unsatisfied_parts(cond, state.facts, state.values, run.tol)
    text = " ".join(format_condition(p, run.task) for p in parts)
    values: dict[str, float] = {}
    for p in parts:
        values.update(fluent_values(p, run.task, state.values))
    undefined = [n for n, v in values.items() if v != v]  # nan: never given a value
    note = f" (undefined: {', '.join(undefined)})" if undefined else ""
    return _fail(
        "goal" if index < 0 else "precondition",
        f"{what} at time {state.time:.6f}: {text} is false{note}",
        max(index, 0),
        state.time,
        condition=text,
        values=values,
        line=line,
    )


def _precondition_fn(run: _Run, action: GroundAction) -> CondFn:
    return per_task(
        run.task,
        ("pre", id(action), run.tol),
        lambda: compile_condition(action.precondition, run.tol),
    )


def _check_happening(
    run: _Run,
    index: int,
    state: State,
    acts: Sequence[tuple[TimedAction, GroundAction]],
    previous: Sequence[tuple[TimedAction, GroundAction]],
) -> None:
    for i, (ta, ga) in enumerate(acts):
        for tb, gb in [*acts[i + 1 :], *previous]:
            if interferes(ga, gb):
                raise _fail(
                    "mutex",
                    f"mutex violation: {ga.signature} at {ta.time:.6f} and {gb.signature} at "
                    f"{tb.time:.6f} interfere (separate them by more than {run.tolerance} s)",
                    index,
                    ta.time,
                    line=ta.line,
                )
    for ta, ga in acts:
        if not _precondition_fn(run, ga)(state.facts, state.values):
            what = f"precondition of {ga.signature} (happening {index})"
            raise _condition_failure(run, ga.precondition, state, what, index, ta.line)


def run_plan(
    task: Task,
    plan: Plan,
    *,
    tol: Tolerances = VAL_TOLERANCES,
    config: FlowConfig = DEFAULT_FLOW,
    tolerance: float = 0.001,
    check: bool = True,
    extend: float = 0.0,
    tick: Callable[[], None] | None = None,
    initial_events: bool = False,
) -> ValidationReport:
    """Simulate ``plan``; with ``check`` also judge it (module docstring).

    ``extend`` [s]: keep simulating (events included) that long after the plan's end, so the
    trajectory predicts what happens next; the goal is still checked at the plan's end.
    ``tick()`` is called before every happening; what it raises (a caller's time limit) ends
    the run. ``initial_events``: accept an initial state in which events are enabled (they
    fire at time 0); VAL refuses such a problem, and so does the check by default.
    """
    run = _Run(task, tol, config, tolerance, check, tick)
    traj = Trajectory(task.fluents)
    state = initial_state(task)
    traj.rows.append(TrajectoryRow(0.0, "init", state.values, "init"))
    report = ValidationReport(True, trajectory=traj, events=traj.events)
    try:
        if check and not initial_events:
            _check_initial_events(run, state)
        state, flow = _run_happenings(run, plan, state, traj)
        traj.final_state = state
        if check and not holds_values(task.goal, state.facts, state.values, tol):
            n = len(_groups(plan))
            where = (
                f"the plan's end ({state.time:.6f})" if plan.end else f"the last happening ({n})"
            )
            raise _condition_failure(run, task.goal, state, f"goal at {where}", -1, None)
        if extend > 0:
            try:
                res = advance(
                    task,
                    state,
                    state.time + extend,
                    tol,
                    config,
                    on_event=_on_event(traj),
                    flow=flow,
                )
            except EventError as exc:
                raise _fail("event", str(exc), len(_groups(plan)) + 1, exc.time) from None
            traj.segments.extend(res.segments)
            state, flow = res.state, res.flow  # type: ignore[assignment]
        traj.segments.append(Segment(state.time, float("inf"), flow))
        traj.end = state.time
    except _Failure as f:
        report = f.report
        report.trajectory, report.events = traj, traj.events
    except (InvalidPlanError, ZeroDivisionError) as exc:  # Zeno, unsettled events, x / 0
        t = traj.rows[-1].time if traj.rows else 0.0
        what = "division by zero" if isinstance(exc, ZeroDivisionError) else str(exc)
        report = ValidationReport(False, f"{what} (after time {t:.6f})", "error", time=t)
        report.trajectory, report.events = traj, traj.events
    return report


def enabled_initial_events(task: Task, tol: Tolerances = VAL_TOLERANCES) -> list[GroundAction]:
    """The events whose precondition holds in the initial state (read as VAL reads it)."""
    state = initial_state(task)
    return [e for e in task.events if holds_values(e.precondition, state.facts, state.values, tol)]


def _check_initial_events(run: _Run, state: State) -> None:
    enabled = enabled_initial_events(run.task, run.tol)
    if enabled:
        names = ", ".join(e.signature for e in enabled[:3]) + (" ..." if len(enabled) > 3 else "")
        raise _fail("event", f"event preconditions hold in the initial state ({names}): VAL "
                    "does not allow an event at time 0", 0, 0.0,
                    condition=format_condition(enabled[0].precondition, run.task))


def _on_event(
    traj: Trajectory, after: bool = False
) -> Callable[[float, GroundAction, State], None]:
    def cb(t: float, e: GroundAction, s: State) -> None:
        traj.events.append(TimedEvent(t, e.name, e.args, after_actions=after))
        traj.rows.append(TrajectoryRow(t, e.signature, s.values, "event"))

    return cb


def _resolve_all(
    task: Task, groups: list[tuple[float, list[TimedAction]]]
) -> list[list[tuple[TimedAction, GroundAction]]]:
    """The ground action of every plan line, per happening; "bad operator" if one is unknown."""
    resolved = []
    for index, (t, timed) in enumerate(groups, 1):
        pairs = []
        for ta in timed:
            ga = resolve(task, ta)
            if ga is None:
                where = f" (plan line {ta.line})" if ta.line else ""
                reason = f"bad operator {ta.signature} at time {t:.6f}{where}"
                raise _fail("bad-operator", reason, index, t, line=ta.line)
            pairs.append((ta, ga))
        resolved.append(pairs)
    return resolved


def _run_happenings(run: _Run, plan: Plan, state: State, traj: Trajectory) -> tuple[State, Flow]:
    task = run.task
    groups = _groups(plan)
    resolved = _resolve_all(task, groups)
    cb, after_cb = _on_event(traj), _on_event(traj, after=True)
    recent: list[tuple[float, list[tuple[TimedAction, GroundAction]]]] = []
    flow = None
    for index, ((t, _), acts) in enumerate(zip(groups, resolved, strict=True), 1):
        if run.tick is not None:
            run.tick()
        try:
            res = advance(task, state, t, run.tol, run.config, on_event=cb, flow=flow)
        except EventError as exc:
            raise _fail("event", str(exc), index, exc.time) from None
        traj.segments.extend(res.segments)
        state = res.state
        if run.check:
            near = [p for tp, g in recent if t - tp < run.tolerance - 1e-9 for p in g]
            _check_happening(run, index, state, acts, near)
        state = apply_actions(task, [g for _, g in acts], state)
        traj.rows.append(TrajectoryRow(t, " ".join(g.signature for _, g in acts), state.values))
        try:
            state, fired, flow = fire_events(task, state, run.tol, run.config)
        except EventError as exc:
            raise _fail("event", str(exc), index, exc.time) from None
        for e in fired:
            after_cb(t, e, state)
        recent = [*recent[-8:], (t, acts)]
    last = groups[-1][0] if groups else 0.0
    if flow is None or (plan.end is not None and plan.end > last + 1e-9):
        # An empty plan settles the initial state; an explicit end lets time run to it.
        until = max(last, plan.end or 0.0)
        try:
            res = advance(task, state, until, run.tol, run.config, on_event=cb, flow=flow)
        except EventError as exc:
            raise _fail("event", str(exc), len(groups) + 1, exc.time) from None
        traj.segments.extend(res.segments)
        state, flow = res.state, res.flow
        if until > last:
            traj.rows.append(TrajectoryRow(until, "end", state.values))
    assert flow is not None
    return state, flow


def validate(
    task: Task,
    plan: Plan,
    tolerance: float = 0.001,
    *,
    tol: Tolerances = VAL_TOLERANCES,
    config: FlowConfig = DEFAULT_FLOW,
    check: Callable[[], None] | None = None,
    initial_events: bool = False,
) -> ValidationReport:
    """Validate ``plan`` against ``task`` with VAL's semantics (module docstring).

    ``check()``, if given, is called before every happening (a caller's time limit: what it
    raises propagates). ``initial_events``: accept events enabled in the initial state (VAL
    refuses them; see :func:`run_plan`)."""
    return run_plan(task, plan, tol=tol, config=config, tolerance=tolerance, check=True,
                    tick=check, initial_events=initial_events)


def simulate(
    task: Task,
    plan: Plan,
    sample_dt: float | None = None,
    *,
    extend: float = 0.0,
    tol: Tolerances = VAL_TOLERANCES,
    config: FlowConfig = DEFAULT_FLOW,
) -> Trajectory:
    """The trajectory of ``plan`` (preconditions and goal not checked).

    ``sample_dt`` [s]: add sampled rows; ``extend`` [s]: simulate on after the plan's end.
    Raises InvalidPlanError for an action the task does not know or an event triggered twice.
    """
    report = run_plan(task, plan, tol=tol, config=config, check=False, extend=extend)
    if not report.valid:
        raise InvalidPlanError(report.reason)
    traj = report.trajectory
    assert traj is not None
    if sample_dt:
        end = traj.final_state.time + extend if traj.final_state is not None else None
        traj.add_samples(sample_dt, end)
    return traj
