"""The ``artiplan`` engine in unified-planning's factory: registration, parameters, statuses,
limits, and problems built with unified-planning's API (nonlinear change included)."""

from __future__ import annotations

import math
import time
from fractions import Fraction

import pytest
import unified_planning as up
from unified_planning.engines import PlanGenerationResultStatus as S
from unified_planning.engines import ValidationResultStatus as V
from unified_planning.exceptions import UPUsageError
from unified_planning.model import (
    DurativeAction,
    Event,
    Fluent,
    InstantaneousAction,
    Problem,
    Process,
)
from unified_planning.shortcuts import (
    GE,
    Equals,
    Not,
    OneshotPlanner,
    PlanValidator,
    RealType,
    get_environment,
)

import artiplan.up
from artiplan.search.api import PlannerConfig
from artiplan.up.convert import END_ACTION, to_pddl

get_environment().credits_stream = None


def _tank(rate_of_level: bool = False, goal: float = 10.0) -> Problem:
    """A pump fills a tank: linear (dx/dt = 2), or nonlinear (dx/dt = 0.5 x) with
    ``rate_of_level``; the goal is a level, no action can end the plan there."""
    on, x = Fluent("on"), Fluent("x", RealType())
    start = InstantaneousAction("start")
    start.add_precondition(Not(on))
    start.add_effect(on, True)
    fill = Process("fill")
    fill.add_precondition(on)
    fill.add_increase_continuous_effect(x, x * Fraction(1, 2) if rate_of_level else 2)
    pb = Problem("tank")
    pb.add_fluent(on, default_initial_value=False)
    pb.add_fluent(x, default_initial_value=1)
    pb.add_action(start)
    pb.add_process(fill)
    pb.add_goal(GE(x, goal))
    return pb


def test_registered_under_one_name_for_both_modes() -> None:
    factory = get_environment().factory
    assert "artiplan" in factory.engines
    artiplan.up.register()  # idempotent
    assert factory.engines.count("artiplan") == 1
    with OneshotPlanner(name="artiplan") as p, PlanValidator(name="artiplan") as v:
        assert p.name == v.name == "artiplan"
    # chosen by problem kind too, for a PDDL+ problem of a kind artiplan supports
    assert artiplan.up.ArtiplanEngine.supports(_tank().kind)


def test_linear_plan_ends_by_waiting() -> None:
    pb = _tank()
    with OneshotPlanner(name="artiplan") as planner:
        res = planner.solve(pb, timeout=30)
    assert res.status is S.SOLVED_SATISFICING
    assert [str(a.action.name) for _, a, _ in res.plan.timed_actions] == ["start"]
    # x = 1 + 2 t reaches 10 at t = 4.5; the plan ends there, after the planner's goal margin
    # (the added end action, dropped)
    end = float(res.metrics["plan_end"])
    assert 4.5 < end <= 4.5 + PlannerConfig().goal_margin + 2e-3
    assert float(res.metrics["engine_internal_time"]) > 0
    assert int(res.metrics["expanded"]) >= 1
    with PlanValidator(name="artiplan") as v:
        ok = v.validate(pb, res.plan)
        strict = PlanValidator(name="artiplan", params={"end": "last-happening"})
        no = strict.validate(pb, res.plan)
    assert ok.status is V.VALID and ok.metrics["end_rule"] == "first-goal"
    assert float(ok.metrics["plan_end"]) == pytest.approx(4.5, abs=1e-6)
    assert no.status is V.INVALID and no.reason.name == "UNSATISFIED_GOALS"
    assert "(<= 10 (x)) is false" in no.metrics["reason"]  # UP's writer puts x on the right
    assert "(x) = 1.000000" in no.log_messages[0].message


def test_nonlinear_continuous_effects_exact_enough() -> None:
    """dx/dt = x / 2 from 1: x = exp(t / 2) reaches 10 at t = 2 ln 10 (numeric fallback)."""
    pb = _tank(rate_of_level=True)
    assert "NON_LINEAR_CONTINUOUS_EFFECTS" in pb.kind.features
    with OneshotPlanner(name="artiplan") as planner:
        res = planner.solve(pb, timeout=30)
    assert res.status is S.SOLVED_SATISFICING
    with PlanValidator(name="artiplan") as v:
        verdict = v.validate(pb, res.plan)
    assert verdict.status is V.VALID
    assert float(verdict.metrics["plan_end"]) == pytest.approx(2 * math.log(10), abs=2e-3)


def test_end_action_only_when_needed() -> None:
    pb = _tank()
    assert END_ACTION in to_pddl(pb).domain
    pb.add_action(InstantaneousAction("wait"))  # a no-effect action of the problem's own
    assert END_ACTION not in to_pddl(pb).domain
    with OneshotPlanner(name="artiplan") as planner:
        res = planner.solve(pb, timeout=30)
    names = [str(a.action.name) for _, a, _ in res.plan.timed_actions]
    assert names == ["start", "wait"] and "plan_end" not in res.metrics
    with PlanValidator(name="artiplan") as v:
        assert v.validate(pb, res.plan).metrics["end_rule"] == "last-happening"


def test_unsolvable_proven() -> None:
    pb = _tank()
    never = Fluent("never")
    pb.add_fluent(never, default_initial_value=False)
    pb.add_goal(never)
    with OneshotPlanner(name="artiplan") as planner:
        res = planner.solve(pb, timeout=30)
    assert res.status is S.UNSOLVABLE_PROVEN and res.plan is None


def _endless() -> Problem:
    """A search without end: three actions cycle a phase and add 1 to x each; the goal
    x = 0.5 is unreachable (x stays integral), which relaxed reachability cannot see."""
    x = Fluent("x", RealType())
    phases = [Fluent(f"phase{k}") for k in range(3)]
    pb = Problem("endless")
    pb.add_fluent(x, default_initial_value=0)
    for k, ph in enumerate(phases):
        pb.add_fluent(ph, default_initial_value=k == 0)
    for k, ph in enumerate(phases):
        step = InstantaneousAction(f"step{k}")
        step.add_precondition(ph)
        step.add_effect(ph, False)
        step.add_effect(phases[(k + 1) % 3], True)
        step.add_increase_effect(x, 1)
        pb.add_action(step)
    pb.add_goal(Equals(x, Fraction(1, 2)))
    return pb


def test_time_limit_honoured() -> None:
    t0 = time.perf_counter()
    with OneshotPlanner(name="artiplan") as planner:
        res = planner.solve(_endless(), timeout=1.0)
    took = time.perf_counter() - t0
    assert res.status is S.TIMEOUT, res.log_messages
    assert 0.9 < took < 2.5


def test_parameters_checked() -> None:
    with pytest.raises(UPUsageError, match="valid:"):
        OneshotPlanner(name="artiplan", params={"speed": 1})
    with pytest.raises(UPUsageError, match="end must be one of"):
        PlanValidator(name="artiplan", params={"end": "later"})
    with pytest.raises(UPUsageError, match="true or false"):
        OneshotPlanner(name="artiplan", params={"improve": "maybe"})
    p = OneshotPlanner(name="artiplan", params={"improve": "false", "epsilon": "0.002",
                                                 "memory_limit": "2048"})
    res = p.solve(_tank(), timeout=30)
    assert res.status is S.SOLVED_SATISFICING and res.metrics["improve_expanded"] == "0"


def test_durative_actions_refused_not_crashed() -> None:
    pb = _tank()
    da = DurativeAction("slow")
    da.set_fixed_duration(3)
    pb.add_action(da)
    assert not artiplan.up.ArtiplanEngine.supports(pb.kind)
    with pytest.warns(UserWarning):
        res = OneshotPlanner(name="artiplan").solve(pb)
    assert res.status is S.UNSUPPORTED_PROBLEM
    assert "CONTINUOUS_TIME" in res.log_messages[0].message


def test_event_triggered_twice_is_invalid_with_explanation() -> None:
    """An event whose effect leaves its precondition true: VAL's 'triggered twice'."""
    pb = _tank()
    flag = Fluent("flag")
    pb.add_fluent(flag, default_initial_value=False)
    loop = Event("loop")
    loop.add_precondition(GE(pb.fluent("x")(), 3))
    loop.add_effect(flag, True)
    pb.add_event(loop)
    pb.add_action(InstantaneousAction("wait"))
    start, wait = pb.action("start"), pb.action("wait")
    plan = up.plans.TimeTriggeredPlan([(Fraction(0), up.plans.ActionInstance(start), None),
                                       (Fraction(6), up.plans.ActionInstance(wait), None)])
    with PlanValidator(name="artiplan") as v:
        res = v.validate(pb, plan)
    assert res.status is V.INVALID
    assert res.metrics["failure_kind"] == "event"
    assert "loop" in res.metrics["reason"] and "twice" in res.metrics["reason"]
    assert float(res.metrics["failure_time"]) == pytest.approx(1.0, abs=1e-6)
