"""``PlanValidator(name="artiplan")`` agrees with ``artiplan.semantics.validate`` on suite plans
and their mutants, maps failures to unified-planning's reasons, and reads up-enhsp's plans."""

from __future__ import annotations

import random
import shutil
import sys
from pathlib import Path

import pytest
import unified_planning as up
from unified_planning.engines import ValidationResultStatus as V
from unified_planning.shortcuts import OneshotPlanner, PlanValidator, get_environment

import artiplan
import artiplan.up
from artiplan.encoding import domain_pddl, make_goal, make_task, problem_pddl
from artiplan.encoding.suite import SUITE_MODELS
from artiplan.model import ArticulatedObject
from artiplan.pddl import load_task
from artiplan.up.convert import to_pddl, to_up_plan

# The mutation generator is a benchmark tool (benchmarks/plan_mutations.py), reused here.
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from plan_mutations import mutations  # noqa: E402
from up_validator_agreement import judge_both  # noqa: E402

get_environment().credits_stream = None


def _suite_problem(label: str, size: int, task_no: int) -> tuple[str, str]:
    options = dict(SUITE_MODELS)[label]
    task = make_task(size, task_no)
    obj = ArticulatedObject(size)
    goal = make_goal(obj, task.target, "threshold", task.seed, planes=options.planes)
    text = problem_pddl(obj, task.initial, task.target, options, goal=goal, name=task.name)
    return domain_pddl(None, options), text


@pytest.mark.parametrize(("label", "size", "task_no"),
                         [("ng", 4, 2), ("ucm-0.5", 5, 1), ("uacm-0.1", 4, 3), ("ucm-1.0", 6, 4)])
def test_agrees_with_artiplan_on_mutants(label: str, size: int, task_no: int) -> None:
    domain, problem = _suite_problem(label, size, task_no)
    res = artiplan.plan(domain, problem, time_limit=60)
    assert res.plan is not None
    task = load_task(domain, problem)
    up_problem = artiplan.up.read_pddl(domain, problem)
    conv = to_pddl(up_problem)
    rows = []
    with PlanValidator(name="artiplan") as validator:
        for name, plan in [("original", res.plan), *mutations(res.plan, random.Random(7))]:
            rows.append((name, judge_both(task, up_problem, validator, conv, plan)))
    assert rows[0][1]["ours"] == "valid"
    disagree = [(n, r) for n, r in rows if not r["agree"]]
    assert not disagree, disagree
    kinds = {r["ours"] for _, r in rows}
    assert "goal" in kinds and len(kinds) >= 3  # the mutants do exercise several failures


def test_reasons_map_to_unified_planning() -> None:
    domain, problem = _suite_problem("ucm-0.1", 4, 1)
    up_problem = artiplan.up.read_pddl(domain, problem)
    with OneshotPlanner(name="artiplan") as planner:
        plan = planner.solve(up_problem, timeout=60).plan
    items = list(plan.timed_actions)
    assert len(items) >= 2
    tt = up.plans.TimeTriggeredPlan
    with PlanValidator(name="artiplan") as v:
        # the stop without its start: inapplicable, and the result names that action instance
        stop = [(t, a, d) for t, a, d in items if str(a.action.name).startswith("stop")]
        if stop:
            res = v.validate(up_problem, tt(stop))
            assert res.status is V.INVALID
            assert res.reason.name == "INAPPLICABLE_ACTION"
            assert res.inapplicable_action is stop[0][1]
            assert "precondition" in res.metrics["reason"]
        # cut before the end: the goal
        res = v.validate(up_problem, tt(items[:1]))
        assert res.reason.name == "UNSATISFIED_GOALS" and res.metrics["failure_kind"] == "goal"
        # two starts at one instant: a mutex
        t, a, d = items[0]
        res = v.validate(up_problem, tt([(t, a, d), (t, a, d), *items[1:]]))
        assert res.status is V.INVALID
        assert res.reason.name in ("MUTEX_CONFLICT", "INAPPLICABLE_ACTION")
        # a SequentialPlan has no times: not judged for a problem with processes
        seq = up.plans.SequentialPlan([a for _, a, _ in items])
        res = v.validate(up_problem, seq)
        assert res.status is V.UNKNOWN and "no times" in res.log_messages[0].message


@pytest.mark.java
@pytest.mark.slow
def test_up_enhsp_plans_judged() -> None:
    """up-enhsp's plans for processes drop ENHSP's final wait: read with ``first-goal`` they
    are judged where ENHSP meant them to end; the verdict is the exact-time one."""
    if shutil.which("java") is None:
        pytest.skip("no java for ENHSP")
    from unified_planning.test.examples.processes import get_example_problems

    for case in get_example_problems().values():
        with OneshotPlanner(name="enhsp") as enhsp:
            res = enhsp.solve(case.problem, timeout=60)
        assert res.plan is not None
        with PlanValidator(name="artiplan", params={"end": "first-goal"}) as v:
            verdict = v.validate(case.problem, res.plan)
        assert verdict.status is V.VALID, verdict.metrics
        with PlanValidator(name="artiplan", params={"end": "last-happening"}) as v:
            assert v.validate(case.problem, res.plan).status is V.INVALID
    # and a paper problem: ENHSP's discretised plan checked against exact time
    domain, problem = _suite_problem("ng", 3, 1)
    up_problem = artiplan.up.read_pddl(domain, problem)
    with OneshotPlanner(name="enhsp") as enhsp:
        res = enhsp.solve(up_problem, timeout=60)
    if res.plan is not None:
        with PlanValidator(name="artiplan", params={"end": "first-goal"}) as v:
            verdict = v.validate(up_problem, res.plan)
        ours = artiplan.semantics.validate(load_task(domain, problem),
                                           _artiplan_plan(res.plan))
        assert (verdict.status is V.VALID) >= ours.valid  # first-goal accepts what VAL does


def _artiplan_plan(plan: object) -> artiplan.semantics.Plan:
    return artiplan.semantics.Plan(tuple(
        artiplan.semantics.TimedAction(float(t), str(a.action.name),
                                       tuple(str(p.object().name) for p in a.actual_parameters))
        for t, a, _ in plan.timed_actions))  # type: ignore[attr-defined]


def test_plan_round_trip() -> None:
    """artiplan plan -> unified-planning plan -> the same artiplan plan."""
    domain, problem = _suite_problem("uacm-0.5", 5, 2)
    res = artiplan.plan(domain, problem, time_limit=60)
    conv = to_pddl(artiplan.up.read_pddl(domain, problem))
    up_plan, end = to_up_plan(conv, res.plan)
    assert end is None  # the suite's domains end plans with observe
    back = _artiplan_plan(up_plan)
    assert [(a.time, a.name.lower(), tuple(x.lower() for x in a.args)) for a in back.actions] \
        == [(a.time, a.name.lower(), tuple(x.lower() for x in a.args)) for a in res.plan.actions]
