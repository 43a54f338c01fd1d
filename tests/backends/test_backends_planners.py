"""Backends: names, missing tools, ENHSP and Kairos on a small problem, limits on a hard one."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from artiplan.backends import PLANNER_NAMES, PlanStatus, get_planner
from artiplan.backends.enhsp import EnhspPlanner
from artiplan.backends.kairos import KairosPlanner
from artiplan.errors import ExitCode, ExternalToolError, UsageError

DATA = Path(__file__).parent / "data"
DOMAIN = DATA / "ng_domain.pddl"
EASY = DATA / "ng3_problem.pddl"
HARD = DATA / "ng12_problem.pddl"  # narrow goal windows: ENHSP (delta 1) cannot finish


def test_unknown_planner_names_the_valid_ones() -> None:
    with pytest.raises(UsageError) as info:
        get_planner("fast-downward")
    for name in PLANNER_NAMES:
        assert name in str(info.value)
    assert info.value.exit_code == ExitCode.USAGE


def test_every_name_gives_its_planner() -> None:
    for name in PLANNER_NAMES:
        assert get_planner(name).name == name


def test_missing_java_is_exit_9(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("PATH", "/nonexistent")
    with pytest.raises(ExternalToolError, match="java") as info:
        EnhspPlanner().solve(DOMAIN, EASY, time_limit=5)
    assert info.value.exit_code == ExitCode.EXTERNAL_TOOL


def test_missing_kairos_is_exit_9(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("PATH", "/nonexistent")
    monkeypatch.setattr(sys, "executable", "/nonexistent/bin/python")
    with pytest.raises(ExternalToolError, match="kairos-planner") as info:
        KairosPlanner().solve(DOMAIN, EASY, time_limit=5)
    assert info.value.exit_code == ExitCode.EXTERNAL_TOOL


@pytest.mark.ci
@pytest.mark.parametrize("name", [pytest.param("enhsp", marks=pytest.mark.java), "kairos"])
def test_external_planner_solves_and_is_measured(name: str) -> None:
    result = get_planner(name).solve(DOMAIN, EASY, time_limit=30, memory_limit=2048)
    assert result.status is PlanStatus.SOLVED, result.raw_output[-500:]
    assert result.plan is not None and len(result.plan) >= 2
    # The goal (l3 xy in (60, 80), z > 120) needs both planes moved: at least two starts.
    starts = [a for a in result.plan.actions if a.name.startswith("start-")]
    assert len(starts) >= 2
    assert result.cpu_s > 0 and result.wall_s > 0 and result.peak_mb > 1


@pytest.mark.slow
@pytest.mark.java
def test_cpu_limit_is_enforced_on_a_hard_problem() -> None:
    limit = 2.0
    result = get_planner("enhsp").solve(DOMAIN, HARD, time_limit=limit, memory_limit=4096)
    assert result.status is PlanStatus.TIMEOUT
    assert result.plan is None
    assert limit * 0.9 <= result.cpu_s <= limit + 3.0  # RLIMIT_CPU hard limit is +2 s
    assert result.wall_s < 3.0 * limit + 30.0


@pytest.mark.slow
@pytest.mark.java
def test_memory_limit_is_enforced_on_a_hard_problem() -> None:
    result = get_planner("enhsp").solve(DOMAIN, HARD, time_limit=60, memory_limit=150)
    assert result.status is PlanStatus.MEMOUT
    assert result.cpu_s < 60


@pytest.mark.java
@pytest.mark.slow
@pytest.mark.ci
def test_an_invalid_peer_plan_exits_4_and_is_written_marked(tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]
                                                           ) -> None:
    """ENHSP (delta 1) misses this suite problem's goal window; `artiplan plan --planner
    enhsp` judges the plan like its own: exit 4, the reason, the plan still written."""
    from artiplan.cli import main
    from artiplan.encoding.suite import suite_problem

    domain_text, problem_text = suite_problem("ucm-0.1", 3, 1)
    domain, problem, out = tmp_path / "d.pddl", tmp_path / "p.pddl", tmp_path / "plan.txt"
    domain.write_text(domain_text)
    problem.write_text(problem_text)
    code = main(["plan", str(domain), str(problem), "--planner", "enhsp", "--time-limit", "60",
                 "-o", str(out)])
    assert code == ExitCode.INVALID_PLAN
    assert "plan is INVALID" in capsys.readouterr().err
    text = out.read_text()
    assert text.startswith("; INVALID (artiplan validate):") and "(start-" in text
