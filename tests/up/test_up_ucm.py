"""The paper's problems through unified-planning: the 4-link UCM task built with the Python API,
and suite problems of every model read from PDDL+ into unified-planning."""

from __future__ import annotations

from pathlib import Path

import pytest
from ucm_api import ucm_problem
from unified_planning.engines import PlanGenerationResultStatus as S
from unified_planning.engines import ValidationResultStatus as V
from unified_planning.plans import TimeTriggeredPlan
from unified_planning.shortcuts import OneshotPlanner, PlanValidator, get_environment

import artiplan
import artiplan.up
from artiplan.encoding import EncodingOptions, domain_pddl, make_goal, make_task, problem_pddl
from artiplan.encoding.suite import SUITE_MODELS
from artiplan.model import PLANES, ArticulatedObject
from artiplan.pddl import load_task
from artiplan.semantics import Plan, TimedAction, validate

get_environment().credits_stream = None


def _as_artiplan(plan: TimeTriggeredPlan) -> Plan:
    return Plan(tuple(TimedAction(float(t), str(a.action.name),
                                  tuple(str(p.object().name) for p in a.actual_parameters))
                      for t, a, _ in plan.timed_actions))


@pytest.mark.parametrize("task_no", [1, 2, 3])
def test_ucm_4_links_built_with_the_api(task_no: int) -> None:
    task = make_task(4, task_no)
    problem = ucm_problem(task)
    assert {"PROCESSES", "EVENTS"} <= problem.kind.features
    with OneshotPlanner(name="artiplan") as planner:
        res = planner.solve(problem, timeout=120)
    assert res.status is S.SOLVED_SATISFICING, res.log_messages
    assert isinstance(res.plan, TimeTriggeredPlan)
    names = [str(a.action.name) for _, a, _ in res.plan.timed_actions]
    assert names[-1] in ("observe", "stop-increase", "stop-decrease")
    with PlanValidator(name="artiplan") as v:
        assert v.validate(problem, res.plan).status is V.VALID
    # the same plan is valid for the encoding's own PDDL+ of this task: the API model is UCM
    obj = ArticulatedObject(4)
    options = EncodingOptions(model="ucm")
    goal = make_goal(obj, task.target, "threshold", task.seed, planes=PLANES)
    text = problem_pddl(obj, task.initial, task.target, options, goal=goal, name=task.name)
    own = load_task(domain_pddl(None, options), text)
    report = validate(own, _as_artiplan(res.plan))
    assert report.valid, report.reason
    # and artiplan's own planner, on that text, finds a plan of the same makespan, up to the
    # ties the search breaks by ground order (UP's writer declares the planes differently)
    direct = artiplan.plan(domain_pddl(None, options), text)
    assert direct.plan is not None
    assert direct.plan.makespan == pytest.approx(_as_artiplan(res.plan).makespan, rel=1e-3)


@pytest.mark.parametrize("label", [label for label, _ in SUITE_MODELS])
def test_suite_problems_read_into_up(tmp_path: Path, label: str) -> None:
    """One 3-link problem of each suite model: read with artiplan.up.read_pddl (UP's reader
    after reordering the operators), solved and validated through unified-planning."""
    options = dict(SUITE_MODELS)[label]
    task = make_task(3, 1)
    obj = ArticulatedObject(3)
    goal = make_goal(obj, task.target, "threshold", task.seed, planes=options.planes)
    domain = domain_pddl(None, options)
    text = problem_pddl(obj, task.initial, task.target, options, goal=goal, name=task.name)
    problem = artiplan.up.read_pddl(domain, text)
    with OneshotPlanner(name="artiplan") as planner:
        res = planner.solve(problem, timeout=120)
    assert res.status is S.SOLVED_SATISFICING, res.log_messages
    with PlanValidator(name="artiplan") as v:
        assert v.validate(problem, res.plan).status is V.VALID
    assert validate(load_task(domain, text), _as_artiplan(res.plan)).valid
