"""Instantaneous change: applying actions (PDDL 2.1) and firing events (VAL's rules).

* Effects are applied in parallel: every condition and every numeric right-hand side is read in
  the state *before* the happening; deletes are applied before adds (an atom both deleted and
  added ends up true); numeric updates of one fluent are applied one after the other, each with
  its right-hand side from the pre-state.
* Events at one time point (:func:`fire_events`): every event whose precondition holds fires, all
  together; then the events triggered by that fire, and so on to a fixpoint. An event triggered
  again at the same time point (in particular one whose effect leaves its own precondition true)
  is an error, :class:`EventError`, as VAL's "Attempt to trigger event twice".
* "Holds" for an event at time t means its precondition holds *at* t (read with the given
  tolerances) or right after t along the current flow (see ``dynamics``): the earliest instant.
* The paper's quirk: facts a process sets (``GroundProcess.discrete``) are true at every
  instant it is active: they are applied whenever the time point settles, with the process
  active (and so re-applied after any happening that deleted them). Numeric discrete effects of
  processes are ignored (they have no meaning at every instant).
"""

from __future__ import annotations

from collections.abc import Sequence

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Effect, GroundAction, Task
from artiplan.semantics.cache import per_task
from artiplan.semantics.dynamics import DEFAULT_FLOW, Flow, FlowConfig, right_holds, settled_flow
from artiplan.semantics.expressions import (
    EXACT,
    CondFn,
    ExprFn,
    Tolerances,
    compile_condition,
    compile_near,
    condition_parts,
    evaluate,
    holds_values,
)
from artiplan.semantics.state import State


class EventError(InvalidPlanError):
    """An event triggered twice at one time point (VAL: "Attempt to trigger event twice")."""

    def __init__(self, event: GroundAction, time: float) -> None:
        self.event = event
        self.time = time
        super().__init__(
            f"event {event.signature} triggered twice at time {time:.6f}: its effect does not "
            "falsify its precondition (or a cascade re-triggers it)"
        )


def _collect(effect: Effect, state: State, out: list[Effect]) -> None:
    """``effect`` and, recursively, the conditional parts whose condition holds in ``state``."""
    out.append(effect)
    for ce in effect.conditional:
        if holds_values(ce.condition, state.facts, state.values):
            _collect(ce.effect, state, out)


def apply_effects(effects: Sequence[Effect], state: State) -> State:
    """``state`` after ``effects`` applied in parallel (module docstring); same time."""
    parts: list[Effect] = []
    for e in effects:
        _collect(e, state, parts)
    dels = {f for e in parts for f in e.delete}
    adds = {f for e in parts for f in e.add}
    facts = (state.facts - dels) | adds if (dels or adds) else state.facts
    numeric = [ne for e in parts for ne in e.numeric]
    if not numeric:
        return State(state.time, facts, state.values)
    values = list(state.values)
    for ne in numeric:
        rhs = evaluate(ne.expr, state.values)
        i = ne.fluent
        if ne.op == "assign":
            values[i] = rhs
        elif ne.op == "increase":
            values[i] += rhs
        elif ne.op == "decrease":
            values[i] -= rhs
        elif ne.op == "scale-up":
            values[i] *= rhs
        else:
            values[i] /= rhs
    return State(state.time, facts, tuple(values))


def apply_action(task: Task, action: GroundAction, state: State) -> State:
    """``state`` after ``action`` (its precondition is not checked here; see ``validate``)."""
    return apply_effects([action.effect], state)


def apply_actions(task: Task, actions: Sequence[GroundAction], state: State) -> State:
    """``state`` after ``actions`` applied in parallel at one happening."""
    return apply_effects([a.effect for a in actions], state)


def _process_facts(flow: Flow, state: State) -> State:
    """Apply the facts active processes set (the paper's quirk); ``state`` if none."""
    discrete = [p.discrete for p in flow.processes if p.discrete.add or p.discrete.delete]
    if not discrete:
        return state
    effs = [Effect(add=d.add, delete=d.delete) for d in discrete]
    new = apply_effects(effs, state)
    return state if new.facts == state.facts else new


def _compile_events(
    task: Task, tol: Tolerances, zero_tol: float
) -> list[tuple[GroundAction, CondFn, set[int], ExprFn]]:
    return [
        (
            e,
            compile_condition(e.precondition, tol),
            condition_parts(e.precondition)[1],
            compile_near(e.precondition, zero_tol),
        )
        for e in task.events
    ]


def fire_events(
    task: Task,
    state: State,
    tol: Tolerances = EXACT,
    config: FlowConfig = DEFAULT_FLOW,
) -> tuple[State, list[GroundAction], Flow]:
    """Fire every triggered event at ``state.time``, cascading to a fixpoint.

    Returns the settled state, the events fired (in firing order; one round's events in task
    order) and the flow that starts there. Raises :class:`EventError` when an event is
    triggered twice.
    """
    compiled = per_task(
        task, ("events", tol, config.zero_tol), lambda: _compile_events(task, tol, config.zero_tol)
    )
    fired: list[GroundAction] = []
    seen: set[int] = set()
    for _ in range(len(task.events) + 2 * len(task.processes) + 2):
        flow = settled_flow(task, state, config)
        with_facts = _process_facts(flow, state)
        if with_facts is not state:
            state = with_facts
            continue
        triggered = [
            (k, e)
            for k, (e, fn, reads, near) in enumerate(compiled)
            if fn(state.facts, state.values)
            or (reads & flow.changing and near(state.values) and right_holds(e.precondition, flow))
        ]
        if not triggered:
            return state, fired, flow
        for k, e in triggered:
            if k in seen:
                raise EventError(e, state.time)
        state = apply_effects([e.effect for _, e in triggered], state)
        seen.update(k for k, _ in triggered)
        fired.extend(e for _, e in triggered)
    raise InvalidPlanError(f"events and process facts do not settle at time {state.time:.6f}")
