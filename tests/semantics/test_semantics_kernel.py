"""The kernel: compiled conditions against the tree walks, exact flows and their roots, right
limits at boundaries, event cascades, parallel effects, the numeric fallback's bracketing."""

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
from artiplan.semantics import Kernel, compile_task, evaluate, holds
from artiplan.semantics import polynomial as P
from artiplan.semantics.compiled import compile_condition
from artiplan.semantics.flow import NumericFlow
from artiplan.tolerances import EXACT, VAL


def _task(processes: tuple[GroundProcess, ...], values: tuple[float, ...], events=(),  # type: ignore[no-untyped-def]
          facts: tuple[str, ...] = (), init: frozenset[int] = frozenset(), actions=()) -> Task:
    names = tuple(f"(v{i})" for i in range(len(values)))
    return Task("d", "p", facts, names, init, values, TRUE, tuple(actions), tuple(events),
                processes)


def _settled(task: Task) -> tuple[Kernel, int, tuple[float, ...], tuple[int, ...]]:
    ct = compile_task(task)
    kernel = Kernel(ct)
    facts, values, active = kernel.settle(0.0, ct.init_facts, ct.init_values, [])
    return kernel, facts, values, active


def test_quadratic_roots_are_stable_when_b_dominates() -> None:
    # x^2 - 1e8 x + 1 = 0: the small root is 1e-8; the naive formula loses it entirely.
    roots = P.positive_roots((1.0, -1e8, 1.0))
    assert roots[0] == pytest.approx(1e-8, rel=1e-12)
    assert roots[1] == pytest.approx(1e8, rel=1e-12)


def test_roots_of_a_cubic_and_a_touching_quadratic() -> None:
    assert P.positive_roots((-6.0, 11.0, -6.0, 1.0)) == pytest.approx([1.0, 2.0, 3.0], abs=1e-12)
    assert P.positive_roots((4.0, -4.0, 1.0)) == [2.0]  # (t - 2)^2 touches zero
    assert P.positive_roots((1.0, 0.0, 1.0)) == []


def test_shift_gives_taylor_coefficients() -> None:
    assert P.shift((1.0, 2.0, 3.0), 2.0) == (17.0, 14.0, 3.0)


def test_compiled_conditions_agree_with_the_tree_walk() -> None:
    rng = random.Random(5)

    def expr(depth: int):  # type: ignore[no-untyped-def]
        if depth == 0 or rng.random() < 0.3:
            return FluentRef(rng.randrange(3)) if rng.random() < 0.6 else Const(rng.uniform(-5, 5))
        if rng.random() < 0.15:
            return Neg(expr(depth - 1))
        return BinOp(rng.choice("+-*"), expr(depth - 1), expr(depth - 1))  # type: ignore[arg-type]

    ct = compile_task(_task((), (0.0, 0.0, 0.0), facts=("(a)", "(b)")))
    for tol in (VAL, EXACT):
        for _ in range(200):
            e = expr(4)
            values = tuple(rng.uniform(-10, 10) for _ in range(3))
            cond = Or((And((Comparison(rng.choice(["<", "<=", ">", ">=", "="]), e, Const(0.0)),
                            Atom(0))), Not(Atom(1))))
            facts = rng.randrange(4)
            fn, _ = compile_condition(cond, ct.comps, tol)
            assert fn(facts, values) == holds(cond, facts, values, tol)
            assert isinstance(evaluate(e, values), float)


def test_linear_flow_and_its_next_change() -> None:
    kernel, facts, values, active = _settled(ng_task(355.0))
    # ng_task starts at rest; start the rotation by hand: the flag fact MOVING
    facts |= 1
    active, flow = kernel.flow(facts, values)
    assert flow.exact and flow.changing == {ANGLE}
    assert flow.coeffs[ANGLE] == (10.0,) and SPEED not in flow.coeffs
    dt = kernel.next_change(values, flow, kernel.comps_for(flow, "dynamic"))
    assert dt == pytest.approx(0.5)  # 355 + 10 t reaches 360 (the wrap event)
    assert kernel.next_change(values, flow, kernel.comps_for(flow, "dynamic"), 0.4) is None


def test_quadratic_flow_uacm() -> None:
    kernel, facts, values, active = _settled(uacm_task(90.0, acc=2.0))
    flow = kernel.flow_of(active, values)
    assert flow.exact
    assert flow.coeffs[VEL] == (2.0,)
    assert flow.coeffs[ANGLE] == (0.0, -1.0)  # 90 - t^2
    dt = kernel.next_change(values, flow, kernel.comps_for(flow, "dynamic"))
    assert dt == pytest.approx(math.sqrt(45.0), abs=1e-12)  # the landing event at 45


def test_cubic_flow_is_exact() -> None:
    # x' = y, y' = z, z' = 1 from 0: x = t^3 / 6 reaches 36 at t = 6.
    procs = (GroundProcess("jerk", (), TRUE, (
        ContinuousEffect(0, FluentRef(1)), ContinuousEffect(1, FluentRef(2)),
        ContinuousEffect(2, Const(1.0)))),)
    goal = Comparison(">=", FluentRef(0), Const(36.0))
    task = Task("d", "p", (), ("(x)", "(y)", "(z)"), frozenset(), (0.0, 0.0, 0.0), goal, (), (),
                procs)
    kernel, facts, values, active = _settled(task)
    flow = kernel.flow_of(active, values)
    assert flow.exact and flow.coeffs[0] == pytest.approx((0.0, 0.0, 1 / 6))
    assert kernel.next_change(values, flow, tuple(kernel.ct.goal_comps)) == pytest.approx(6.0)


def test_polynomial_rates_are_integrated_exactly() -> None:
    # v' = 1 from 0, x' = v^2: x = t^3 / 3 (a power of a changing fluent, still exact).
    procs = (GroundProcess("go", (), TRUE, (
        ContinuousEffect(1, Const(1.0)),
        ContinuousEffect(0, BinOp("^", FluentRef(1), Const(2.0))))),)
    goal = Comparison(">=", FluentRef(0), Const(9.0))
    task = Task("d", "p", (), ("(x)", "(v)"), frozenset(), (0.0, 0.0), goal, (), (), procs)
    kernel, facts, values, active = _settled(task)
    flow = kernel.flow_of(active, values)
    assert flow.exact
    assert kernel.next_change(values, flow, tuple(kernel.ct.goal_comps)) == pytest.approx(3.0)


def test_non_polynomial_flow_brackets_its_crossings() -> None:
    # x' = x from 1: x = e^t reaches 2 at ln 2 (numeric flow, error reported).
    procs = (GroundProcess("grow", (), TRUE, (ContinuousEffect(0, FluentRef(0)),)),)
    goal = Comparison(">=", FluentRef(0), Const(2.0))
    task = Task("d", "p", (), ("(x)",), frozenset(), (1.0,), goal, (), (), procs)
    kernel, facts, values, active = _settled(task)
    flow = kernel.flow_of(active, values)
    assert isinstance(flow, NumericFlow) and not flow.exact
    assert flow.values(values, 1.0)[0] == pytest.approx(math.e, rel=1e-9)
    dt = kernel.next_change(values, flow, tuple(kernel.ct.goal_comps), 1.0)
    assert dt == pytest.approx(math.log(2.0), abs=1e-8)
    assert flow.error < 1e-8


def test_a_numeric_flow_is_integrated_once_per_start_values_and_answers_as_a_new_one() -> None:
    # x' = x from two start values: asking again with equal values (a new tuple) gets the
    # same flow back, with the answers of a flow made afresh
    procs = (GroundProcess("grow", (), TRUE, (ContinuousEffect(0, FluentRef(0)),)),)
    task = Task("d", "p", (), ("(x)",), frozenset(), (1.0,), TRUE, (), (), procs)
    kernel, facts, values, active = _settled(task)
    first = kernel.flow_of(active, values)
    other = kernel.flow_of(active, (2.0,))
    again = kernel.flow_of(active, tuple(list(values)))
    assert again is first and other is not first
    fresh = Kernel(kernel.ct).flow_of(active, values)
    assert fresh is not first
    for dt in (0.3, 1.7, 0.9):
        assert again.values(values, dt) == fresh.values(values, dt)
    assert other.values((2.0,), 1.0)[0] == pytest.approx(2.0 * math.e, rel=1e-9)


def test_numeric_fallback_finds_a_crossing_between_two_samples() -> None:
    # x = sin-like motion: x' = y, y' = -x (a cycle: numeric). From (0, 1): x = sin t. The
    # condition x > 0.999999 holds only in a 2.8 ms window around pi/2: a touch a fixed scan
    # of 0.5 s steps would miss; the enclosures must not.
    procs = (GroundProcess("osc", (), TRUE, (
        ContinuousEffect(0, FluentRef(1)), ContinuousEffect(1, Neg(FluentRef(0))))),)
    goal = Comparison(">", FluentRef(0), Const(0.999999))
    task = Task("d", "p", (), ("(x)", "(y)"), frozenset(), (0.0, 1.0), goal, (), (), procs)
    kernel, facts, values, active = _settled(task)
    flow = kernel.flow_of(active, values)
    dt = kernel.next_change(values, flow, tuple(kernel.ct.goal_comps), 3.0)
    assert dt is not None and abs(dt - math.pi / 2) < 2e-3


def test_process_stops_exactly_at_its_boundary() -> None:
    free = And((Comparison(">", FluentRef(0), Const(0.0)),
                Comparison("<", FluentRef(0), Const(180.0))))
    procs = (GroundProcess("gravity", (), free, (ContinuousEffect(0, Const(-1.0)),)),)
    kernel, facts, values, active = _settled(_task(procs, (2.0,)))
    segments: list = []
    facts, values, active = kernel.advance(0.0, facts, values, 5.0, [], active, segments)
    assert values[0] == pytest.approx(0.0, abs=1e-12)
    assert [round(s.t1, 12) for s in segments] == [2.0, 5.0]
    assert active == ()


def test_process_starts_on_its_boundary_by_the_rate() -> None:
    procs = (
        GroundProcess("rise", (), TRUE, (ContinuousEffect(0, Const(1.0)),)),
        GroundProcess("follow", (), Comparison(">", FluentRef(0), Const(0.0)),
                      (ContinuousEffect(1, Const(2.0)),)),
    )
    kernel, facts, values, active = _settled(_task(procs, (0.0, 0.0)))
    assert active == (0, 1)  # the right limit of (> x 0) holds: follow starts at once
    assert kernel.flow_of(active, values).values(values, 1.5) == (1.5, 3.0)


def test_parallel_effects_read_the_pre_state_and_delete_before_add() -> None:
    a = GroundAction("a", (), TRUE, Effect(add=(0,), numeric=(
        NumericEffect("assign", 0, FluentRef(1)),)))
    b = GroundAction("b", (), TRUE, Effect(delete=(0,), numeric=(
        NumericEffect("assign", 1, FluentRef(0)),)))
    ct = compile_task(_task((), (3.0, 4.0), facts=("(f)",), actions=(a, b)))
    facts, values = Kernel.apply(ct.actions, 0b1, (3.0, 4.0))
    assert facts == 0b1 and values == (4.0, 3.0)  # a swap, (f) both deleted and added


def test_process_discrete_facts_hold_while_active() -> None:
    # The paper's quirk: a process that sets (falling) keeps it true while active.
    proc = GroundProcess("gravity", (), Atom(0), (ContinuousEffect(0, Const(-1.0)),),
                         discrete=Effect(add=(1,)))
    clear = GroundAction("clear", (), TRUE, Effect(delete=(1,)))
    task = _task((proc,), (5.0,), facts=("(free)", "(falling)"), init=frozenset({0}),
                 actions=(clear,))
    kernel, facts, values, active = _settled(task)
    assert facts >> 1 & 1
    facts, values = kernel.ct.actions[0].effect(facts, values)
    assert not facts >> 1 & 1
    facts, values, _ = kernel.settle(0.0, facts, values, [])
    assert facts >> 1 & 1  # restored: the process is still active


def test_event_cascade_fires_in_rounds() -> None:
    # e1: (>= x 1) -> x := 0, (a); e2: (a) -> not (a), y += 1. Both fire once at t = 1, 2.
    e1 = GroundAction("e1", (), Comparison(">=", FluentRef(0), Const(1.0)),
                      Effect(add=(0,), numeric=(NumericEffect("assign", 0, Const(0.0)),)),
                      kind="event")
    e2 = GroundAction("e2", (), Atom(0), Effect(delete=(0,), numeric=(
        NumericEffect("increase", 1, Const(1.0)),)), kind="event")
    rise = GroundProcess("rise", (), TRUE, (ContinuousEffect(0, Const(1.0)),))
    task = _task((rise,), (0.0, 0.0), events=(e1, e2), facts=("(a)",))
    kernel, facts, values, active = _settled(task)
    log: list[tuple[float, int]] = []
    facts, values, active = kernel.advance(0.0, facts, values, 2.5, log, active)
    assert [(round(t, 12), i) for t, i in log] == [(1.0, 0), (1.0, 1), (2.0, 0), (2.0, 1)]
    assert values == pytest.approx((0.5, 2.0))


def test_a_flow_that_blows_up_is_no_crash() -> None:
    # v' = -(v^2): from v = -1 the speed reaches -inf at t = 1; an interval power and an RK4
    # step overflow on the way (they raised OverflowError): nothing is found beyond
    from artiplan.pddl import load_task
    from artiplan.semantics.walks import interval

    domain = """(define (domain blow) (:requirements :fluents :time)
      (:predicates (on)) (:functions (v) (d))
      (:process fall :parameters () :precondition (and (on))
        :effect (and (decrease (v) (* #t (^ (v) 2))) (increase (d) (* #t 1)))))"""
    problem = """(define (problem blow-1) (:domain blow)
      (:init (on) (= (v) -1) (= (d) 0)) (:goal (and (>= (d) 100))))"""
    task = load_task(domain, problem)
    ct = compile_task(task)
    kernel = Kernel(ct)
    facts, values, active = kernel.settle(0.0, ct.init_facts, ct.init_values, [])
    flow = kernel.flow_of(active, values)
    assert isinstance(flow, NumericFlow)
    goal = tuple(sorted(ct.goal_comps))
    assert kernel.next_change(values, flow, goal, 60.0) is None
    power = BinOp("^", FluentRef(0), Const(2.0))
    assert interval(power, lambda i: (1e200, 1e201))[1] == math.inf
