"""Warnings for harmless oddities, and the parse/ground commands (exit codes, output)."""

from __future__ import annotations

from pathlib import Path

import pytest

from artiplan.cli import main
from artiplan.pddl import load_task, parse_domain, parse_problem

SMALL = """(define (domain w)
  (:requirements :strips :typing :conditional-effects :made-up-feature)
  (:types thing)
  (:predicates (p ?x - thing) (q))
  (:action a :parameters (?x - thing) :precondition (p ?x) :effect (q)))
"""

SMALL_PROBLEM = """(define (problem wp) (:domain other-name)
  (:requirements :strips :unknown-too)
  (:objects A b - thing)
  (:init (p A) (not (q)) (= (undeclared-f A) 2))
  (:goal (q)))
"""


def test_requirement_warnings() -> None:
    domain = parse_domain(SMALL, "w.pddl")
    text = "\n".join(domain.warnings)
    assert "w.pddl:1:1: unknown requirement :made-up-feature" in text
    assert "requirement :conditional-effects is declared but not used" in text
    assert ":typing" not in text and ":strips" not in text  # used / umbrella
    assert len(domain.warnings) == 2


def test_problem_warnings() -> None:
    task = load_task(SMALL, SMALL_PROBLEM)
    text = "\n".join(task.warnings)
    assert "names domain 'other-name'" in text
    assert "unknown requirement :unknown-too" in text
    assert "'(not ...)' in :init ignored" in text
    assert "function 'undeclared-f' is initialised but never declared" in text
    # the file still grounds: (a A) can apply, (a b) can never ((p b) is static and false)
    assert [a.signature for a in task.actions] == ["(a A)"]
    assert task.fluents == ()


def test_value_given_twice_warns() -> None:
    domain = SMALL.replace("(:predicates", "(:functions (f))\n  (:predicates")
    problem = SMALL_PROBLEM.replace("(not (q))", "(= (f) 1) (= (F) 2)")
    task = load_task(domain, problem)
    assert any("F is initialised twice" in w for w in task.warnings)
    assert task.init_values == ()  # (f) is static and unused: folded away


def test_byte_order_mark_and_crlf_are_accepted() -> None:
    domain = parse_domain("\ufeff" + SMALL.replace("\n", "\r\n"), "bom.pddl")
    assert domain == parse_domain(SMALL)
    assert domain.operators[0].loc is not None and domain.operators[0].loc.line == 5


def test_names_are_case_insensitive_but_keep_their_spelling() -> None:
    problem = SMALL_PROBLEM.replace("(p A)", "(P a)").replace("(:goal (q))", "(:GOAL (Q))")
    task = load_task(SMALL.upper().replace(":MADE-UP-FEATURE", ""), problem)
    assert [a.signature for a in task.actions] == ["(A A)"]  # operator spelled as declared
    assert task.facts == ("(Q)",)
    assert task.action_by_signature("(a a)").name == "A"
    assert parse_problem(problem).objects[0].name == "A"


@pytest.fixture
def files(tmp_path: Path, arm_domain: str, arm_problem: str) -> tuple[Path, Path]:
    d, p = tmp_path / "domain.pddl", tmp_path / "problem.pddl"
    d.write_text(arm_domain)
    p.write_text(arm_problem)
    return d, p


def test_parse_command(files: tuple[Path, Path], capsys: pytest.CaptureFixture[str]) -> None:
    d, p = files
    assert main(["parse", str(d), str(p)]) == 0
    out, err = capsys.readouterr()
    assert "domain ARTI: 2 types, 6 predicates, 3 functions, 2 actions, 3 processes, 1 events" \
        in out
    assert "ok (2 warnings)" in out
    assert f"warning: {d}:31:" in err


def test_parse_print_round_trips(files: tuple[Path, Path], capsys: pytest.CaptureFixture[str],
                                 tmp_path: Path) -> None:
    d, _ = files
    assert main(["parse", str(d), "--print"]) == 0
    out, _ = capsys.readouterr()
    assert parse_domain(out) == parse_domain(d.read_text())


def test_ground_command(files: tuple[Path, Path], capsys: pytest.CaptureFixture[str]) -> None:
    d, p = files
    assert main(["ground", str(d), str(p), "--list"]) == 0
    out, _ = capsys.readouterr()
    assert "facts 11, fluents 6, actions 8, events 6, processes 9, pruned 46" in out
    assert "  (start-increase L1 L2 z-axis)" in out
    assert "  (propagate L2 L3 xy-axes)" in out
    assert main(["ground", str(d), str(p), "--facts"]) == 0
    out, _ = capsys.readouterr()
    assert "  (free-to-move L2)  (initially true)" in out
    assert "  (in-use)\n" in out
    assert "  (angle L2 z-axis) = -3\n" in out and "  (angle L3 xy-axes) = 0.001\n" in out


def test_bad_input_exits_3_with_location(tmp_path: Path,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "bad.pddl"
    bad.write_text("(define (domain x)\n  (:predicates (p))\n  (:action a :precondition (q)))\n")
    assert main(["parse", str(bad)]) == 3
    _, err = capsys.readouterr()
    assert f"{bad}:3:28: undeclared predicate 'q'" in err
    assert main(["ground", str(bad), str(bad)]) == 3
    assert main(["parse", str(tmp_path / "missing.pddl")]) == 3
