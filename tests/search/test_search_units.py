"""Unit tests of the planner's parts on hand-built tiny tasks (artiplan.pddl.task dataclasses)."""

from __future__ import annotations

import math

import pytest

from artiplan.pddl.task import (
    TRUE,
    And,
    Atom,
    Comparison,
    Const,
    ContinuousEffect,
    Effect,
    FluentRef,
    GroundAction,
    GroundProcess,
    Not,
    NumericEffect,
    Or,
    Task,
)
from artiplan.search.api import PlanStatus, plan_task
from artiplan.search.intervals import Jump, condition_set, travel
from artiplan.search.waits import Waits, grid_after
from artiplan.semantics import Kernel, compile_task

X, V = FluentRef(0), FluentRef(1)
ON = 0


def _task(processes: tuple[GroundProcess, ...], goal, events=()) -> Task:  # type: ignore[no-untyped-def]
    start = GroundAction("start", (), Not(Atom(ON)), Effect(add=(ON,)))
    stop = GroundAction("stop", (), Atom(ON), Effect(delete=(ON,)))
    observe = GroundAction("observe", (), TRUE, Effect())
    return Task("d", "p", ("(on)",), ("(x)", "(v)"), frozenset(), (1.0, 0.0), goal,
                (start, stop, observe), tuple(events), processes)


LINEAR = GroundProcess("move", (), Atom(ON), (ContinuousEffect(0, Const(2.0)),))
ACCEL = (
    GroundProcess("accelerate", (), Atom(ON), (ContinuousEffect(1, Const(1.0)),)),
    GroundProcess("move", (), Atom(ON), (ContinuousEffect(0, V),)),
)


def _running(task: Task) -> tuple[Waits, int, tuple[float, ...], tuple[int, ...]]:
    ct = compile_task(task)
    kernel = Kernel(ct)
    facts, values, active = kernel.settle(0.0, 1 << ON, ct.init_values, [])
    return Waits(kernel), facts, values, active


def test_wait_stops_just_after_a_linear_crossing() -> None:
    dyn, facts, values, active = _running(_task((LINEAR,), Comparison(">", X, Const(5.0))))
    res = dyn.next(0.0, facts, values, [], active)
    assert res is not None
    t, _, vals, _ = res
    assert t == grid_after(2.0, 1e-6)  # x = 1 + 2t crosses 5 at t = 2
    assert 2.0 < t < 2.00001
    assert vals[0] == pytest.approx(1.0 + 2.0 * t)


def test_wait_solves_a_quadratic_exactly() -> None:
    dyn, facts, values, active = _running(_task(ACCEL, Comparison(">", X, Const(5.0))))
    res = dyn.next(0.0, facts, values, [], active)
    assert res is not None
    # x = 1 + t^2 / 2 crosses 5 at t = sqrt(8)
    assert res[0] == pytest.approx(math.sqrt(8.0), abs=3e-6)
    assert res[0] > math.sqrt(8.0)


def test_event_fires_at_its_exact_time_and_jumps() -> None:
    jump = GroundAction("reset", (), Comparison(">=", X, Const(3.0)),
                        Effect(numeric=(NumericEffect("assign", 0, Const(-10.0)),)), "event")
    task = _task((LINEAR,), Comparison(">", X, Const(100.0)), (jump,))
    dyn, facts, values, active = _running(task)
    log: list[tuple[float, int]] = []
    facts, values, _ = dyn.kernel.advance(0.0, facts, values, 2.0, log, active)
    assert log == [(pytest.approx(1.0), 0)]  # x = 1 + 2t reaches 3 at t = 1
    assert values[0] == pytest.approx(-10.0 + 2.0 * 1.0)


def test_travel_follows_wrap_around_jumps() -> None:
    target = condition_set(Comparison(">", X, Const(300.0)), 0)
    assert target is not None
    wrap = (Jump(((-math.inf, -0.01),), 1.0, 360.0),)
    assert travel(50.0, 1.0, target, wrap) == pytest.approx(250.0)
    assert travel(50.0, -1.0, target, wrap) == pytest.approx(50.01)  # down through 0, wraps
    across = Or((Comparison(">", X, Const(355.0)), Comparison("<", X, Const(5.0))))
    window = condition_set(across, 0)
    assert window is not None and travel(3.0, 1.0, window, ()) == 0.0


def test_planner_on_a_tiny_task_ends_with_observe() -> None:
    task = _task((LINEAR,), And((Comparison(">", X, Const(5.0)), Comparison("<", X, Const(6.0)))))
    result = plan_task(task, time_limit=10)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.plan is not None
    names = [a.name for a in result.plan.actions]
    assert names[0] == "start" and names[-1] in ("observe", "stop")
    assert 2.0 < result.plan.makespan < 2.5


def test_planner_proves_a_constant_goal_unsolvable() -> None:
    task = _task((LINEAR,), Comparison(">", V, Const(1.0)))  # nothing changes v
    assert plan_task(task).status is PlanStatus.UNSOLVABLE_PROVEN


def test_non_polynomial_dynamics_use_the_numeric_flow() -> None:
    growth = GroundProcess("grow", (), Atom(ON), (ContinuousEffect(0, X),))  # x' = x: e^t
    task = _task((growth,), Comparison(">", X, Const(5.0)))
    result = plan_task(task, time_limit=30)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.stats["numeric_flows"] > 0
    assert result.plan is not None
    # the goal wait runs on for the goal margin (0.01 s) while the goal keeps holding
    assert math.log(5.0) - 1e-3 <= result.plan.makespan <= math.log(5.0) + 0.01 + 1e-3


def test_memory_limit_is_detected() -> None:
    from artiplan.search.limits import LimitReached, Limits

    limits = Limits(memory_limit=1.0, every=1)
    ballast = [bytearray(1 << 20) for _ in range(64)]  # 64 MB more than at the start
    with pytest.raises(LimitReached) as info:
        limits.check()
    assert info.value.kind == "memory"
    del ballast
