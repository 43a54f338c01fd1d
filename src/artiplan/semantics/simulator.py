"""Letting time pass exactly between happenings.

:func:`advance` moves from one time point to another, stopping at every critical instant: where
an event's precondition becomes true or a process's precondition changes (a process starts or
stops). Critical instants are roots of polynomials (``dynamics``), not steps of a clock.
Simulating and validating whole plans: ``validator`` (``simulate``, ``validate``).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Condition, GroundAction, Task
from artiplan.semantics.cache import per_task
from artiplan.semantics.dynamics import DEFAULT_FLOW, Flow, FlowConfig, crossing_time
from artiplan.semantics.expressions import EXACT, Tolerances, condition_parts
from artiplan.semantics.happenings import fire_events
from artiplan.semantics.state import State

#: Two instants closer than this [s] are the same instant (float noise of t + dt).
TIME_EPS = 1e-9


@dataclass(frozen=True)
class Segment:
    """The flow that holds on [t0, t1] [s]."""

    t0: float
    t1: float
    flow: Flow


@dataclass
class AdvanceResult:
    """What :func:`advance` returns.

    Attributes:
        state: The settled state at ``until`` (events there fired).
        events: ``(time, event)`` in firing order, with exact times [s].
        segments: The flows between critical instants, in time order.
        flow: The flow that starts at ``state``.
    """

    state: State
    events: list[tuple[float, GroundAction]] = field(default_factory=list)
    segments: list[Segment] = field(default_factory=list)
    flow: Flow | None = None


def _watched(task: Task) -> list[tuple[Condition, set[int]]]:
    """Conditions whose change is critical: event and process preconditions, with fluents read."""
    conds = [e.precondition for e in task.events] + [p.precondition for p in task.processes]
    return [(c, condition_parts(c)[1]) for c in conds]


def next_critical_time(
    task: Task, flow: Flow, horizon: float, tol: Tolerances = EXACT
) -> float | None:
    """Earliest dt in (0, horizon] at which an event may fire or a process start or stop."""
    best: float | None = None
    for cond, reads in per_task(task, "watched", lambda: _watched(task)):
        if not reads & flow.changing:
            continue
        dt = crossing_time(cond, flow, horizon if best is None else best, tol)
        if dt is not None and (best is None or dt < best):
            best = dt
    return best


def advance(
    task: Task,
    state: State,
    until: float,
    tol: Tolerances = EXACT,
    config: FlowConfig = DEFAULT_FLOW,
    max_steps: int = 100_000,
    on_event: Callable[[float, GroundAction, State], None] | None = None,
    flow: Flow | None = None,
) -> AdvanceResult:
    """Let time pass from ``state.time`` to ``until`` [s], firing events exactly.

    Events that hold at ``state.time`` fire first; events whose precondition becomes true at
    exactly ``until`` fire too (before any action there). ``on_event(time, event, state)`` is
    called after each firing round (``state`` after that round's cascade). Pass ``flow`` (the
    flow ``fire_events`` returned for ``state``) when ``state`` is already settled, to skip
    settling it again.
    Raises ``EventError`` (an event triggered twice) or ``InvalidPlanError`` (too many critical
    instants before ``until``: Zeno behaviour).
    """
    if until < state.time - TIME_EPS:
        raise ValueError(f"cannot advance backwards from {state.time} to {until}")
    result = AdvanceResult(state)
    if flow is None or flow.start is not state:
        state, fired, flow = fire_events(task, state, tol, config)
        _record(result, state, fired, on_event)
    for _ in range(max_steps):
        remaining = until - state.time
        if remaining <= TIME_EPS:
            result.state, result.flow = state, flow
            return result
        dt = None if flow.is_static else next_critical_time(task, flow, remaining, tol)
        if dt is None or dt >= remaining - TIME_EPS:
            dt, t_next = remaining, until
        else:
            t_next = state.time + dt
        nxt = flow.state_at(dt)
        result.segments.append(Segment(state.time, t_next, flow))
        state = State(t_next, nxt.facts, nxt.values)
        state, fired, flow = fire_events(task, state, tol, config)
        _record(result, state, fired, on_event)
    raise InvalidPlanError(
        f"more than {max_steps} critical instants between {result.state.time} and {until} "
        "(Zeno behaviour?)"
    )


def _record(
    result: AdvanceResult,
    state: State,
    fired: list[GroundAction],
    on_event: Callable[[float, GroundAction, State], None] | None,
) -> None:
    for e in fired:
        result.events.append((state.time, e))
        if on_event is not None:
            on_event(state.time, e, state)
