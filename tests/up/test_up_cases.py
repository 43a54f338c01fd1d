"""unified-planning's own test problems through ``OneshotPlanner``/``PlanValidator("artiplan")``.

Every case loads (or is reported); supported ones are solved and the plan validated by artiplan
and, for plans without processes, by unified-planning's own sequential validator; the cases'
own valid and invalid plans get the verdicts they are labelled with; unsupported kinds are
refused with UNSUPPORTED_PROBLEM / UNKNOWN, never an exception.
"""

from __future__ import annotations

from typing import Any

import pytest
import unified_planning as up
from unified_planning.engines import PlanGenerationResultStatus as S
from unified_planning.engines import ValidationResultStatus as V
from unified_planning.plans import SequentialPlan, TimeTriggeredPlan
from unified_planning.shortcuts import OneshotPlanner, PlanValidator
from up_cases import load_cases

import artiplan.up  # noqa: F401  (registers the engine)
from artiplan.search.api import PlannerConfig
from artiplan.up.kinds import supports

up.shortcuts.get_environment().credits_stream = None

CASES, ERRORS = load_cases()

def _kind(case: Any) -> Any:
    return case.problem.kind


def _pddl_plus(name: str) -> bool:
    return bool({"PROCESSES", "EVENTS"} & _kind(CASES[name]).features)


SUPPORTED = sorted(n for n, c in CASES.items() if supports(_kind(c)))
UNSUPPORTED = sorted(n for n, c in CASES.items() if not supports(_kind(c)))
PDDL_PLUS = [n for n in SUPPORTED if _pddl_plus(n)]


def test_cases_load() -> None:
    """Only the known-broken module fails to load, and its case is rebuilt."""
    assert set(ERRORS) <= {"up_test_cases.builtin.processes.constant_derivative"}, ERRORS
    assert len(CASES) > 100
    assert len(PDDL_PLUS) >= 3  # 1d_movement, boiling_water, constant_derivative
    assert all(n in SUPPORTED for n in CASES if _pddl_plus(n)), "a PDDL+ case is refused"


def _solve(problem: Any) -> Any:
    with OneshotPlanner(name="artiplan") as planner:
        return planner.solve(problem, timeout=30)


def _validate(problem: Any, plan: Any, **params: Any) -> Any:
    with PlanValidator(name="artiplan", params=params) as validator:
        return validator.validate(problem, plan)


@pytest.mark.parametrize("name", PDDL_PLUS)
def test_pddl_plus_cases_solved_and_validated(name: str) -> None:
    problem = CASES[name].problem
    result = _solve(problem)
    assert result.status is S.SOLVED_SATISFICING, result.log_messages
    assert isinstance(result.plan, TimeTriggeredPlan)
    verdict = _validate(problem, result.plan)
    assert verdict.status is V.VALID, verdict.metrics
    # the plan end the planner reports is at most its margins after the first instant the
    # validator finds the goal (a goal margin past the boundary, an event gap past an event)
    if "plan_end" in result.metrics:
        gap = float(result.metrics["plan_end"]) - float(verdict.metrics["plan_end"])
        config = PlannerConfig()
        assert -1e-3 < gap < config.goal_margin + config.event_gap + 1e-3


@pytest.mark.parametrize("name", SUPPORTED)
def test_supported_cases(name: str) -> None:
    case = CASES[name]
    problem = case.problem
    result = _solve(problem)
    if not case.solvable:
        assert result.status not in (S.SOLVED_SATISFICING, S.SOLVED_OPTIMALLY)
        return
    assert result.status is S.SOLVED_SATISFICING, result.log_messages
    assert _validate(problem, result.plan).status is V.VALID
    if not problem.processes:
        assert isinstance(result.plan, SequentialPlan)
        with PlanValidator(name="sequential_plan_validator") as theirs:
            assert theirs.validate(problem, result.plan).status is V.VALID


@pytest.mark.parametrize("name", [n for n in SUPPORTED
                                  if CASES[n].valid_plans or CASES[n].invalid_plans])
def test_labelled_plans(name: str) -> None:
    """The cases' own plans: artiplan's verdict is the label."""
    case = CASES[name]
    for plan in case.valid_plans:
        assert _validate(case.problem, plan).status is V.VALID, str(plan)
    for plan in case.invalid_plans:
        res = _validate(case.problem, plan)
        assert res.status is V.INVALID, str(plan)
        assert res.reason is not None or res.metrics["failure_kind"] in ("event", "error")


@pytest.mark.parametrize("name", UNSUPPORTED)
def test_unsupported_refused(name: str) -> None:
    problem = CASES[name].problem
    assert not artiplan.up.ArtiplanEngine.supports(problem.kind)
    with pytest.warns(UserWarning, match="cannot establish"):
        result = _solve(problem)
    assert result.status is S.UNSUPPORTED_PROBLEM
    assert result.plan is None
    assert "does not support" in result.log_messages[0].message
    for plan in CASES[name].valid_plans[:1]:
        with pytest.warns(UserWarning):
            assert _validate(problem, plan).status is V.UNKNOWN
