"""artiplan's planner end to end on generated NG/UCM/UACM problems, checked by the validator."""

from __future__ import annotations

import random

import pytest

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.encoding.suite import random_pair
from artiplan.model import ArticulatedObject, Configuration
from artiplan.pddl import load_task
from artiplan.search.api import PlanStatus, plan, plan_task
from artiplan.semantics import validate

MODELS = [
    EncodingOptions("ng"),
    EncodingOptions("ucm", speed_g=1.0),
    EncodingOptions("uacm", acceleration=0.5),
]


def _problem(n: int, options: EncodingOptions, seed: int, style: str = "threshold"):  # type: ignore[no-untyped-def]
    obj = ArticulatedObject(n)
    init, target = random_pair(n, random.Random(seed))
    return domain_pddl(obj, options), problem_pddl(obj, init, target, options, style, seed)


@pytest.mark.parametrize("options", MODELS, ids=lambda o: o.model)
@pytest.mark.parametrize("seed", [1, 2, 3])
def test_small_problems_are_solved_with_valid_plans(options: EncodingOptions, seed: int) -> None:
    domain, problem = _problem(4, options, seed)
    result = plan(domain, problem, time_limit=60)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.plan is not None and len(result.plan) >= 1
    report = validate(load_task(domain, problem), result.plan)  # checked again, independently
    assert report.valid, report.reason
    assert result.stats["validated"] is True
    assert result.stats["expanded"] >= 1


@pytest.mark.parametrize("options", MODELS, ids=lambda o: o.model)
def test_window_goals_across_the_wrap(options: EncodingOptions) -> None:
    domain, problem = _problem(3, options, 7, style="window")
    result = plan(domain, problem, time_limit=60)
    assert result.status is PlanStatus.SOLVED, result.message
    assert validate(load_task(domain, problem), result.plan).valid  # type: ignore[arg-type]


NARROW = """(define (problem narrow) (:domain artiplan-ng)
  (:objects L1 L2 L3 - link)
  (:init (connected L1 L2) (connected L2 L3) (affects L2 L3)
    (free-to-move L1) (free-to-move L2) (free-to-move L3)
    (= (speed-i) 10) (= (speed-d) 10)
    (= (angle L1 xy-axes) 0) (= (angle L1 z-axis) 90)
    (= (angle L2 xy-axes) 0) (= (angle L2 z-axis) 90)
    (= (angle L3 xy-axes) 159.2) (= (angle L3 z-axis) 90))
  (:goal (and (> (angle L3 xy-axes) 193.1) (< (angle L3 xy-axes) 197.3))))
"""


def test_narrow_window_hit_with_an_exact_stop_time() -> None:
    # 10 deg/s: the window is 0.42 s wide, narrower than one 1 s step of a fixed-step planner
    domain = domain_pddl(ArticulatedObject(3), EncodingOptions("ng"))
    result = plan(domain, NARROW, time_limit=30)
    assert result.status is PlanStatus.SOLVED, result.message
    assert result.plan is not None
    report = validate(load_task(domain, NARROW), result.plan)
    assert report.valid, report.reason
    final = report.trajectory.value("(angle L3 xy-axes)", result.plan.makespan)  # type: ignore[union-attr]
    assert 193.1 < final < 197.3
    starts = [a for a in result.plan.actions if a.name == "start-increase"]
    assert starts, "the window is reached by increasing the angle (34 deg away, not 326)"
    # the end is not on a whole second: the wait was computed, not stepped
    assert abs(result.plan.makespan - round(result.plan.makespan)) > 1e-3


def test_same_input_same_plan() -> None:
    domain, problem = _problem(6, EncodingOptions("ucm", speed_g=0.5), 11)
    first = plan(domain, problem, time_limit=60)
    second = plan(domain, problem, time_limit=60)
    assert first.status is PlanStatus.SOLVED
    assert first.plan == second.plan
    assert first.stats["expanded"] == second.stats["expanded"]


def test_goal_on_the_clamped_base_is_proven_unsolvable() -> None:
    obj = ArticulatedObject(3)
    options = EncodingOptions("ucm")
    init = Configuration.from_angles([10, 20, 30], [90, 90, 90])
    domain = domain_pddl(obj, options)
    problem = problem_pddl(obj, init, init, options).replace(
        "(:goal (and", "(:goal (and (> (angle L1 xy-axes) 200)", 1)
    result = plan(domain, problem, time_limit=30)
    assert result.status is PlanStatus.UNSOLVABLE_PROVEN
    assert "L1" in result.message
    assert result.status.exit_code == 5


def test_goal_on_a_constant_fluent_is_proven_unsolvable() -> None:
    domain = domain_pddl(ArticulatedObject(3), EncodingOptions("ng"))
    problem = NARROW.replace("(:goal (and", "(:goal (and (> (speed-i) 20)")
    result = plan(domain, problem, time_limit=30)
    assert result.status is PlanStatus.UNSOLVABLE_PROVEN


def test_time_limit_is_honoured() -> None:
    domain, problem = _problem(12, EncodingOptions("uacm", acceleration=0.1), 5)
    task = load_task(domain, problem)
    result = plan_task(task, time_limit=0.02)
    assert result.status is PlanStatus.TIMEOUT
    assert result.stats["total_s"] < 1.5
    assert result.status.exit_code == 7


def test_unknown_option_is_a_usage_error() -> None:
    from artiplan.errors import UsageError

    with pytest.raises(UsageError, match="epsilon"):
        plan_task(load_task(*_problem(3, EncodingOptions("ng"), 1)), epsilonn=0.1)
