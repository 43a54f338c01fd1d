"""Which attempts go first: a goal fact behind a nonlinear comparison (the rate heuristic
reads linear rates only) starts with the numeric relaxation."""

from __future__ import annotations

from pathlib import Path

from artiplan.pddl import load_task
from artiplan.search.api import goal_behind_comparisons, plan

FAMILIES = Path(__file__).resolve().parents[2] / "benchmarks" / "pddlplus"

DOMAIN = """(define (domain reach)
  (:requirements :fluents :time)
  (:predicates (moving) (done))
  (:functions (x) (y))
  (:process move :parameters () :precondition (moving)
    :effect (and (increase (x) (* #t 1)) (increase (y) (* #t 1))))
  (:action go :parameters () :precondition (not (moving)) :effect (moving))
  (:action finish :parameters () :precondition (and (moving) GATE) :effect (done)))
"""
PROBLEM = """(define (problem p) (:domain reach)
  (:init (= (x) 0) (= (y) 0)) (:goal (done)))
"""


def _task(tmp: Path, gate: str):  # type: ignore[no-untyped-def]
    (tmp / "d.pddl").write_text(DOMAIN.replace("GATE", gate))
    (tmp / "p.pddl").write_text(PROBLEM)
    return load_task(tmp / "d.pddl", tmp / "p.pddl")


def test_a_goal_behind_a_nonlinear_comparison_is_found(tmp_path: Path) -> None:
    assert goal_behind_comparisons(_task(tmp_path, "(>= (* (x) (y)) 4)"))
    # a linear gate is the rate heuristic's to read; no gate at all, nothing to read
    assert not goal_behind_comparisons(_task(tmp_path, "(>= (+ (x) (y)) 4)"))
    assert not goal_behind_comparisons(_task(tmp_path, "(moving)"))


def test_intercept_starts_with_the_numeric_attempt_and_car_linear_does_not() -> None:
    task = load_task(FAMILIES / "intercept" / "domain.pddl", FAMILIES / "intercept" / "p03.pddl")
    assert goal_behind_comparisons(task)
    result = plan(FAMILIES / "intercept" / "domain.pddl", FAMILIES / "intercept" / "p03.pddl")
    assert result.plan is not None and result.stats.attempts == 1  # was the third attempt
    car = FAMILIES / "car_linear"
    assert not goal_behind_comparisons(load_task(car / "domain.pddl", car / "p01.pddl"))


def test_a_nonlinear_gate_is_planned_through(tmp_path: Path) -> None:
    (tmp_path / "d.pddl").write_text(DOMAIN.replace("GATE", "(>= (* (x) (y)) 4)"))
    (tmp_path / "p.pddl").write_text(PROBLEM)
    result = plan(tmp_path / "d.pddl", tmp_path / "p.pddl", time_limit=60)
    assert result.plan is not None
    assert [a.name for a in result.plan.actions] == ["go", "finish"]
    assert result.plan.actions[-1].time >= 2.0 - 1e-3  # x * y = t^2 reaches 4 at t = 2
