"""``artiplan validate`` and ``artiplan simulate``: exit codes, messages, files."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from semantics_builders import TANK, TANK_PROBLEM

from artiplan.cli import main

DOMAIN, PROBLEM = TANK, TANK_PROBLEM


@pytest.fixture
def files(tmp_path: Path) -> tuple[Path, Path]:
    (tmp_path / "d.pddl").write_text(DOMAIN)
    (tmp_path / "p.pddl").write_text(PROBLEM)
    return tmp_path / "d.pddl", tmp_path / "p.pddl"


def _plan(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "plan.txt"
    path.write_text(text)
    return path


def test_valid_plan_exits_0_and_writes_the_trajectory(files, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    plan = _plan(tmp_path, "0: (open)\n4.0: (close)\n")
    out = tmp_path / "t.csv"
    assert main(["validate", *map(str, files), str(plan), "--trajectory", str(out), "-v"]) == 0
    text = capsys.readouterr().out
    assert "; 1.5: (overflow)" in text and "Plan valid" in text
    rows = list(csv.reader(out.open()))
    assert rows[0] == ["time", "happening", "level", "flow-rate"]
    assert [r[1] for r in rows[1:]] == ["init", "(open)", "(overflow)", "(overflow)", "(close)"]


def test_invalid_plan_exits_4_with_the_first_reason(files, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    plan = _plan(tmp_path, "0: (open)\n1.6: (close)\n")
    assert main(["validate", *map(str, files), str(plan)]) == 4
    out = capsys.readouterr().out
    assert "goal" in out and "(level) = 5.300000" in out


def test_bad_operator_exits_4_with_its_line(files, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    plan = _plan(tmp_path, "; a comment\n0: (open)\n1.0: (drain)\n")
    assert main(["validate", *map(str, files), str(plan)]) == 4
    out = capsys.readouterr().out
    assert "bad operator (drain)" in out and "plan line 3" in out


def test_malformed_plan_exits_3_with_a_location(files, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    plan = _plan(tmp_path, "0: (open)\n1.0 (close)\n")
    assert main(["validate", *map(str, files), str(plan)]) == 3
    assert f"{plan}:2:5:" in capsys.readouterr().err


def test_simulate_prints_events_and_draws(files, tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    plan = _plan(tmp_path, "0: (open)\n4.0: (close)\n")
    png, out = tmp_path / "t.png", tmp_path / "t.csv"
    args = ["simulate", *map(str, files), str(plan), "--plot", str(png)]
    assert main([*args, "--trajectory", str(out), "--sample", "0.5"]) == 0
    text = capsys.readouterr().out
    assert text.splitlines()[:3] == ["0.0: (open)", "; 1.5: (overflow)", "; 3.166667: (overflow)"]
    assert png.stat().st_size > 10_000
    samples = [r for r in csv.reader(out.open()) if r[1] == ""]
    assert len(samples) == 9  # 0, 0.5, ..., 4.0


def test_an_event_listed_as_an_action_is_a_bad_operator_except_in_enhsp_files(  # type: ignore[no-untyped-def]
    files, tmp_path, capsys
) -> None:
    val_style = _plan(tmp_path, "0: (open)\n1.5: (overflow)\n4.0: (close)\n")
    assert main(["validate", *map(str, files), str(val_style)]) == 4
    assert "bad operator (overflow)" in capsys.readouterr().out
    enhsp = _plan(tmp_path, "0: (open)\n2.0: (overflow)\n4.0: (close)\n4.0: @PlanEND\n")
    assert main(["validate", *map(str, files), str(enhsp)]) == 0


GROWTH = """
(define (domain growth)
  (:requirements :strips :numeric-fluents :time)
  (:predicates (doubled))
  (:functions (x))
  (:action observe :parameters () :precondition (and) :effect (and))
  (:process grow :parameters () :precondition (and) :effect (increase (x) (* #t (x))))
  (:event double :parameters () :precondition (and (not (doubled)) (>= (x) 2))
    :effect (doubled)))
"""
GROWTH_PROBLEM = "(define (problem g) (:domain growth) (:init (= (x) 1)) (:goal (doubled)))"


def test_non_polynomial_rates_say_so_and_still_time_events(tmp_path, capsys) -> None:  # type: ignore[no-untyped-def]
    (tmp_path / "d.pddl").write_text(GROWTH)
    (tmp_path / "p.pddl").write_text(GROWTH_PROBLEM)
    plan = _plan(tmp_path, "1.0: (observe)\n")
    args = [str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"), str(plan)]
    assert main(["validate", *args, "-v"]) == 0
    out = capsys.readouterr().out
    assert "numeric fallback" in out
    assert "; 0.693147: (double)" in out  # x = e^t reaches 2 at ln 2
