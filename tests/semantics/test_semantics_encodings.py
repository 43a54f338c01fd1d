"""The validator on PDDL text: a hand-written domain, and the project's UCM / UACM encodings.

Expected values are worked out by hand in each test from the model's rates.
"""

from __future__ import annotations

import math

import pytest
from semantics_builders import TANK, TANK_PROBLEM

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.model import ArticulatedObject, Configuration
from artiplan.pddl import load_task
from artiplan.semantics import validate
from artiplan.semantics.plan_io import parse_plan


def test_hand_written_domain_events_change_rates() -> None:
    task = load_task(TANK, TANK_PROBLEM)
    # 7 at 2/s: 10 at t = 1.5 -> 5, rate 3; 10 again at 1.5 + 5/3 -> 5, rate 4; at 4: 8.
    plan = parse_plan("0: (open)\n4.0: (close)\n")
    report = validate(task, plan)
    assert report.valid, report.reason
    times = [e.time for e in report.events]
    assert times == pytest.approx([1.5, 1.5 + 5 / 3], abs=1e-9)
    assert report.trajectory is not None
    assert report.trajectory.value("(level)", 4.0) == pytest.approx(5 + 4 * (4 - 1.5 - 5 / 3))
    bad = validate(task, parse_plan("0: (open)\n1.6: (close)\n"))  # 5.3 at 1.6
    assert not bad.valid and bad.values == {"(level)": pytest.approx(5.3)}


def _encoded(model: str, goal: str, **opts: float) -> tuple[str, str]:
    obj = ArticulatedObject(3)
    init = Configuration((0.0, 350.0, 100.0), (0.0, 90.0, 120.0))
    options = EncodingOptions(model, **opts)  # type: ignore[arg-type]
    problem = problem_pddl(obj, init, init, options)
    problem = problem[: problem.index("(:goal")] + f"(:goal (and {goal}))\n)\n"
    return domain_pddl(obj, options), problem


def test_ucm_rotation_wrap_and_gravity_by_hand() -> None:
    # speed-g 0.5. Holding L2 (0..2 s) stops L2's fall; L3 falls at 0.5 alone, then at 1.0
    # (its own 0.5 + L2's propagated 0.5). L2 xy: 350 + 10 t wraps at t = 1.
    domain, problem = _encoded(
        "ucm", "(> (angle L3 xy-axes) 115) (< (angle L3 z-axis) 117.5)", speed_g=0.5
    )
    task = load_task(domain, problem)
    plan = "0: (start-increase L1 L2 xy-axes)\n2.0: (stop-increase L1 L2 xy-axes)\n"
    report = validate(task, parse_plan(plan + "4.0: (observe)\n"))
    assert report.valid, report.reason
    assert [(e.name, e.args) for e in report.events] == [("back-to-zero", ("L2", "xy-axes"))]
    assert report.events[0].time == pytest.approx(1.0, abs=1e-9)
    traj = report.trajectory
    assert traj is not None
    assert traj.value("angle(L2,z-axis)", 2.0) == pytest.approx(90.0)
    assert traj.value("angle(L3,z-axis)", 2.0) == pytest.approx(119.0)
    assert traj.value("angle(L2,z-axis)", 4.0) == pytest.approx(89.0)
    assert traj.value("angle(L3,z-axis)", 4.0) == pytest.approx(117.0)
    assert traj.value("angle(L2,xy-axes)", 4.0) == pytest.approx(10.0)
    early = validate(task, parse_plan(plan + "3.0: (observe)\n"))  # L3 z still 118
    assert not early.valid and early.kind == "goal"
    assert early.values == {"(angle L3 z-axis)": pytest.approx(118.0)}
    assert traj.value("angle(L3,xy-axes)", 3.0) == pytest.approx(120.0)  # stopped at 2 s


def test_uacm_quadratic_fall_and_exact_event_cascade() -> None:
    # acceleration 2: from t = 0 gravity acts on L2 and L3 (flags set in the initial state,
    # speeds from 0). L2 z = 90 - t^2, L3 z = 120 - 2 t^2 (its own fall plus L2's). L3 reaches
    # 0 at sqrt(60): its gravity stops (its angle set to 0), but L2's keeps carrying it down:
    # -(t^2 - 60) reaches -0.2 (the wrap margin) at sqrt(60.2), where L3 wraps to 359.8 and,
    # above 181 (the hysteresis), starts falling the other way from speed 0.
    domain, problem = _encoded("uacm", "(> (angle L2 z-axis) 80.5)", acceleration=2.0)
    task = load_task(domain, problem)
    report = validate(task, parse_plan("3.0: (observe)\n"))
    assert report.valid, report.reason
    traj = report.trajectory
    assert traj is not None
    assert traj.value("angle(L2,z-axis)", 3.0) == pytest.approx(81.0, abs=1e-9)
    assert traj.value("angle(L3,z-axis)", 3.0) == pytest.approx(102.0, abs=1e-9)

    long = validate(task, parse_plan("7.8: (observe)\n"))
    t1, t2 = math.sqrt(60.0), math.sqrt(60.2)
    fired = [(e.name, e.args[0], e.time) for e in long.events if e.args[0] == "L3"]
    assert [(n, a) for n, a, _ in fired] == [
        ("stop-gravity-decrease", "L3"),
        ("back-to-360", "L3"),
        ("start-gravity-increase", "L3"),
    ]
    assert [t for *_, t in fired] == pytest.approx([t1, t2, t2], abs=1e-9)
    assert abs(fired[0][2] - t1) < 1e-9 and abs(fired[1][2] - t2) < 1e-9
    t = 7.8
    expected = 359.8 + (t - t2) ** 2 - (t**2 - t2**2)
    assert long.trajectory is not None
    assert long.trajectory.value("angle(L3,z-axis)", t) == pytest.approx(expected, abs=1e-9)


FIG7 = """
(define (domain fig7)
  (:requirements :strips :typing :numeric-fluents :time)
  (:types link)
  (:predicates (free-to-move ?l - link) (increasing-angle-gravity ?l - link))
  (:functions (angle ?l - link) (speed-g))
  (:action grab :parameters (?l - link) :precondition (free-to-move ?l)
     :effect (and (not (free-to-move ?l)) (not (increasing-angle-gravity ?l))))
  (:action observe :parameters () :precondition (and) :effect (and))
  (:process gravity-increase
    :parameters (?l1 - link)
    :precondition (and (free-to-move ?l1) (> (angle ?l1) 180) (< (angle ?l1) 360))
    :effect (and (increase (angle ?l1) (* #t (speed-g))) (increasing-angle-gravity ?l1))))
"""
FIG7_PROBLEM = """(define (problem q) (:domain fig7) (:objects L2 - link)
  (:init (free-to-move L2) (= (angle L2) 200) (= (speed-g) 2))
  (:goal (and (increasing-angle-gravity L2) (> (angle L2) 205))))"""


def test_papers_process_with_a_boolean_effect_sets_it_while_active() -> None:
    task = load_task(FIG7, FIG7_PROBLEM)
    assert any("gravity-increase" in w for w in task.warnings)
    ok = validate(task, parse_plan("3: (observe)\n"))  # 206 deg, the fact set by the process
    assert ok.valid, ok.reason
    # Grabbing at 1 s stops the process (202 deg) and clears the fact: both goals fail.
    bad = validate(task, parse_plan("1: (grab L2)\n3: (observe)\n"))
    assert not bad.valid
    assert bad.condition == "(increasing-angle-gravity L2) (> (angle L2) 205)"
    assert bad.values == {"(angle L2)": pytest.approx(202.0)}
