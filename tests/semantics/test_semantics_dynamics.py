"""Flows, crossing times and events: exact polynomials, boundaries, the numeric fallback."""

from __future__ import annotations

import math
import random

import pytest
from semantics_builders import ANGLE, SPEED, VEL, ng_task, uacm_task

from artiplan.pddl.task import (
    TRUE,
    And,
    Atom,
    BinOp,
    Comparison,
    Const,
    ContinuousEffect,
    Effect,
    FluentRef,
    GroundAction,
    GroundProcess,
    Neg,
    Not,
    NumericEffect,
    Or,
    Task,
)
from artiplan.semantics import (
    State,
    advance,
    compile_condition,
    compile_expr,
    crossing_time,
    evaluate,
    fire_events,
    holds,
    initial_state,
    make_flow,
    settled_flow,
)
from artiplan.semantics import polynomial as P
from artiplan.semantics.happenings import apply_effects


def _state(values: tuple[float, ...], facts: frozenset[int] = frozenset()) -> State:
    return State(0.0, facts, values)


def test_quadratic_roots_are_stable_when_b_dominates() -> None:
    # x^2 - 1e8 x + 1 = 0: the small root is 1e-8; the naive formula loses it entirely.
    roots = P.positive_roots((1.0, -1e8, 1.0))
    assert roots[0] == pytest.approx(1e-8, rel=1e-12)
    assert roots[1] == pytest.approx(1e8, rel=1e-12)


def test_roots_of_a_cubic_and_a_touching_quadratic() -> None:
    # (t - 1)(t - 2)(t - 3) = t^3 - 6 t^2 + 11 t - 6
    assert P.positive_roots((-6.0, 11.0, -6.0, 1.0)) == pytest.approx([1.0, 2.0, 3.0], abs=1e-12)
    assert P.positive_roots((4.0, -4.0, 1.0)) == [2.0]  # (t - 2)^2 touches zero
    assert P.positive_roots((1.0, 0.0, 1.0)) == []


def test_shift_gives_taylor_coefficients() -> None:
    p = (1.0, 2.0, 3.0)  # 1 + 2t + 3t^2; at t = 2: 17, slope 14, curvature 3
    assert P.shift(p, 2.0) == (17.0, 14.0, 3.0)


def test_compiled_expressions_and_conditions_agree_with_the_tree_walk() -> None:
    rng = random.Random(5)

    def expr(depth: int):  # type: ignore[no-untyped-def]
        if depth == 0 or rng.random() < 0.3:
            return FluentRef(rng.randrange(3)) if rng.random() < 0.6 else Const(rng.uniform(-5, 5))
        op = rng.choice("+-*")
        if rng.random() < 0.15:
            return Neg(expr(depth - 1))
        return BinOp(op, expr(depth - 1), expr(depth - 1))  # type: ignore[arg-type]

    for _ in range(200):
        e = expr(4)
        values = [rng.uniform(-10, 10) for _ in range(3)]
        assert compile_expr(e)(values) == pytest.approx(evaluate(e, values))
        cond = Or((And((Comparison(rng.choice(["<", "<=", ">", ">=", "="]), e, Const(0.0)),
                        Atom(0))), Not(Atom(1))))
        facts = frozenset(rng.sample([0, 1], rng.randrange(3)))
        assert compile_condition(cond)(facts, values) == holds(cond, State(0, facts, tuple(values)))


def test_linear_flow_and_crossing_time() -> None:
    task = ng_task(355.0)
    state = State(0.0, frozenset({0}), (355.0, 10.0, 0.0, 0.0))  # moving
    flow = settled_flow(task, state)
    assert flow.exact and flow.changing == {ANGLE}
    assert flow.coefficients(ANGLE) == (355.0, 10.0)
    assert flow.coefficients(SPEED) == (10.0,)
    cond = Comparison(">=", FluentRef(ANGLE), Const(360.0))
    assert crossing_time(cond, flow) == 0.5
    assert crossing_time(cond, flow, horizon=0.4) is None
    # A strict comparison changes at the same instant (the infimum of where it holds).
    assert crossing_time(Comparison(">", FluentRef(ANGLE), Const(360.0)), flow) == 0.5


def test_quadratic_flow_coefficients_uacm() -> None:
    task = uacm_task(90.0, acc=2.0)
    flow = settled_flow(task, initial_state(task))
    assert flow.exact
    assert flow.coefficients(VEL) == (0.0, 2.0)
    assert flow.coefficients(ANGLE) == (90.0, 0.0, -1.0)
    landed = task.events[0].precondition
    assert crossing_time(landed, flow) == pytest.approx(math.sqrt(45.0), abs=1e-12)


def test_cubic_flow_uses_polynomial_roots() -> None:
    # x' = y, y' = z, z' = 1 from 0: x = t^3 / 6 reaches 36 at t = 6.
    procs = (GroundProcess("jerk", (), TRUE, (
        ContinuousEffect(0, FluentRef(1)), ContinuousEffect(1, FluentRef(2)),
        ContinuousEffect(2, Const(1.0)))),)
    task = Task("d", "p", (), ("(x)", "(y)", "(z)"), frozenset(), (0.0, 0.0, 0.0), TRUE, (), (),
                procs)
    flow = make_flow(task, initial_state(task), procs)
    assert flow.exact and flow.coefficients(0) == pytest.approx((0.0, 0.0, 0.0, 1 / 6))
    t = crossing_time(Comparison(">=", FluentRef(0), Const(36.0)), flow)
    assert t == pytest.approx(6.0, abs=1e-9)


def test_non_polynomial_flow_falls_back_to_rk4_and_brentq() -> None:
    # x' = x from 1: x = e^t reaches 2 at ln 2. Not polynomial: Flow.exact is False.
    procs = (GroundProcess("grow", (), TRUE, (ContinuousEffect(0, FluentRef(0)),)),)
    task = Task("d", "p", (), ("(x)",), frozenset(), (1.0,), TRUE, (), (), procs)
    flow = make_flow(task, initial_state(task), procs)
    assert not flow.exact and flow.coefficients(0) is None
    assert flow.values_at(1.0)[0] == pytest.approx(math.e, rel=1e-10)
    t = crossing_time(Comparison(">=", FluentRef(0), Const(2.0)), flow, horizon=1.0)
    assert t == pytest.approx(math.log(2.0), abs=1e-8)


def test_process_stops_exactly_at_its_boundary() -> None:
    # Gravity lowers the angle at 1 deg/s while 0 < angle < 180: from 2 it stops at t = 2.
    free = And((Comparison(">", FluentRef(0), Const(0.0)),
                Comparison("<", FluentRef(0), Const(180.0))))
    procs = (GroundProcess("gravity", (), free, (ContinuousEffect(0, Const(-1.0)),)),)
    task = Task("d", "p", (), ("(angle)",), frozenset(), (2.0,), TRUE, (), (), procs)
    result = advance(task, initial_state(task), 5.0)
    assert result.state.time == 5.0
    assert result.state.values[0] == pytest.approx(0.0, abs=1e-12)
    assert [round(s.t1, 12) for s in result.segments] == [2.0, 5.0]
    assert result.flow is not None and result.flow.is_static


def test_process_starts_on_its_boundary_by_the_rate() -> None:
    # x rises at 1 from 0; a process on (> x 0) starts right away (its right limit holds).
    procs = (
        GroundProcess("rise", (), TRUE, (ContinuousEffect(0, Const(1.0)),)),
        GroundProcess("follow", (), Comparison(">", FluentRef(0), Const(0.0)),
                      (ContinuousEffect(1, Const(2.0)),)),
    )
    task = Task("d", "p", (), ("(x)", "(y)"), frozenset(), (0.0, 0.0), TRUE, (), (), procs)
    flow = settled_flow(task, initial_state(task))
    assert {p.name for p in flow.processes} == {"rise", "follow"}
    assert flow.values_at(1.5) == (1.5, 3.0)


def test_parallel_effects_read_the_pre_state_and_delete_before_add() -> None:
    s = State(1.0, frozenset({0}), (3.0, 4.0))
    a = Effect(add=(0,), numeric=(NumericEffect("assign", 0, FluentRef(1)),))
    b = Effect(delete=(0,), numeric=(NumericEffect("assign", 1, FluentRef(0)),))
    out = apply_effects([a, b], s)
    assert out.facts == frozenset({0}) and out.values == (4.0, 3.0)  # a swap


def test_process_discrete_facts_hold_while_active() -> None:
    # The paper's quirk: a process that sets (falling) keeps it true while active.
    proc = GroundProcess("gravity", (), Atom(0), (ContinuousEffect(0, Const(-1.0)),),
                         discrete=Effect(add=(1,)))
    clear = GroundAction("clear", (), TRUE, Effect(delete=(1,)))
    task = Task("d", "p", ("(free)", "(falling)"), ("(angle)",), frozenset({0}), (5.0,), TRUE,
                (clear,), (), (proc,))
    state, fired, flow = fire_events(task, initial_state(task))
    assert 1 in state.facts and not fired
    after = apply_effects([clear.effect], state)
    assert 1 not in after.facts
    settled, _, _ = fire_events(task, after)
    assert 1 in settled.facts  # restored: the process is still active


def test_event_cascade_fires_in_rounds() -> None:
    # e1: (>= x 1) -> x := 0, (a); e2: (a) -> not (a), y += 1. Both fire once at t = 1.
    e1 = GroundAction("e1", (), Comparison(">=", FluentRef(0), Const(1.0)),
                      Effect(add=(0,), numeric=(NumericEffect("assign", 0, Const(0.0)),)),
                      kind="event")
    e2 = GroundAction("e2", (), Atom(0), Effect(delete=(0,), numeric=(
        NumericEffect("increase", 1, Const(1.0)),)), kind="event")
    rise = GroundProcess("rise", (), TRUE, (ContinuousEffect(0, Const(1.0)),))
    task = Task("d", "p", ("(a)",), ("(x)", "(y)"), frozenset(), (0.0, 0.0), TRUE, (),
                (e1, e2), (rise,))
    result = advance(task, initial_state(task), 2.5)
    assert [(round(t, 12), e.name) for t, e in result.events] == [
        (1.0, "e1"), (1.0, "e2"), (2.0, "e1"), (2.0, "e2")
    ]
    assert result.state.values == pytest.approx((0.5, 2.0))
