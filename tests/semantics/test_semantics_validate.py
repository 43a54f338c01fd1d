"""Hand-made valid and invalid plans on NG and UACM style dynamics; expected values by hand."""

from __future__ import annotations

import math

import pytest
from semantics_builders import (
    ANGLE,
    VEL,
    Comparison,
    Effect,
    GroundAction,
    NumericEffect,
    c,
    f,
    ng_task,
    uacm_task,
    wrap_events,
)

from artiplan.semantics import Plan, TimedAction, simulate, validate
from artiplan.tolerances import EXACT

ROT = ("L1", "L2", "z-axis")


def start(t: float) -> TimedAction:
    return TimedAction(t, "start-increase", ROT)


def stop(t: float) -> TimedAction:
    return TimedAction(t, "stop-increase", ROT)


def observe(t: float) -> TimedAction:
    return TimedAction(t, "observe")


def test_wrap_event_fires_exactly_when_the_angle_reaches_360() -> None:
    # 355 deg + 10 deg/s from t = 0.3: reaches 360 at 0.8, wraps to 0; at 1.3 it is 5.
    report = validate(ng_task(355.0), Plan((start(0.3), stop(1.3))))
    assert report.valid, report.reason
    assert [e.name for e in report.events] == ["back-to-zero"]
    assert report.events[0].time == pytest.approx(0.8, abs=1e-9)
    traj = report.trajectory
    assert traj is not None
    assert traj.value("(angle L2 z-axis)", 0.55) == pytest.approx(357.5, abs=1e-9)
    assert traj.value("angle(L2,z-axis)", 1.05) == pytest.approx(2.5, abs=1e-9)
    assert traj.value("(angle L2 z-axis)", 3.0) == pytest.approx(5.0, abs=1e-9)  # stopped


def test_decreasing_angle_wraps_at_the_margin() -> None:
    # 5 deg at -10 deg/s: reaches -0.01 at 0.501 s and becomes 359.99; at 0.6 s 359.0.
    report = validate(ng_task(5.0, speed=-10.0), Plan((start(0.0), stop(0.6))))
    assert report.valid, report.reason
    assert [(e.name, e.time) for e in report.events] == [("back-to-360", pytest.approx(0.501))]
    assert abs(report.events[0].time - 0.501) < 1e-9
    assert report.trajectory is not None
    assert report.trajectory.final_state is not None
    assert report.trajectory.final_state.values[ANGLE] == pytest.approx(359.0, abs=1e-9)


def test_goal_is_checked_only_at_the_last_happening() -> None:
    task = ng_task(50.0, goal=Comparison(">", f(ANGLE), c(100.0)))
    # The rotation reaches 100 deg at t = 5: an observe at 6 sees 110 deg.
    assert validate(task, Plan((start(0.0), observe(6.0)))).valid
    early = validate(task, Plan((start(0.0), observe(4.0))))
    assert not early.valid and early.kind == "goal"
    assert early.values == {"(angle L2 z-axis)": pytest.approx(90.0)}
    # Without a final happening nothing is checked after t = 0, although the angle gets there.
    assert not validate(task, Plan((start(0.0),))).valid


def test_goal_true_midway_but_false_at_the_end_is_invalid() -> None:
    task = ng_task(50.0, goal=Comparison("<", f(ANGLE), c(80.0)))
    report = validate(task, Plan((start(0.0), stop(5.0))))  # true until t = 3, 100 deg at 5
    assert not report.valid
    assert report.kind == "goal"
    assert report.values["(angle L2 z-axis)"] == pytest.approx(100.0)


def test_stop_then_start_at_one_instant_is_a_mutex_violation() -> None:
    plan = Plan((start(0.0), stop(1.0), start(1.0), stop(2.0)))
    report = validate(ng_task(10.0), plan)
    assert not report.valid and report.kind == "mutex"
    assert report.happening == 2 and report.time == pytest.approx(1.0)


def test_actions_apart_by_the_tolerance_are_fine_closer_ones_interfere() -> None:
    task = ng_task(10.0)
    assert validate(task, Plan((start(0.0), stop(1.0), start(1.001), stop(2.0)))).valid
    close = validate(task, Plan((start(0.0), stop(1.0), start(1.0005), stop(2.0))))
    assert not close.valid and close.kind == "mutex"
    assert validate(task, Plan((start(0.0), stop(1.0), start(1.0005), stop(2.0))), 0.0001).valid


def test_failed_precondition_names_happening_condition_and_line() -> None:
    report = validate(ng_task(10.0), Plan((TimedAction(1.0, "stop-increase", ROT, line=7),)))
    assert not report.valid and report.kind == "precondition"
    assert report.happening == 1 and report.line == 7
    assert report.condition == "(moving L2 z-axis)"


def test_an_unknown_action_is_a_bad_operator() -> None:
    plan = Plan((start(0.0), TimedAction(1.0, "fly", ("L2",), line=2)))
    report = validate(ng_task(10.0), plan)
    assert not report.valid and report.kind == "bad-operator"
    assert report.line == 2 and "fly" in report.reason
    # An event written as an action is a bad operator too (VAL).
    as_action = validate(ng_task(10.0), Plan((TimedAction(0.0, "back-to-zero", ROT[1:]),)))
    assert as_action.kind == "bad-operator"


def test_an_event_that_does_not_falsify_its_precondition_is_an_error() -> None:
    # (>= angle 20) -> increase vel: still true afterwards. 10 deg at 10 deg/s: t = 1 exactly.
    sticky = GroundAction("sticky", (), Comparison(">=", f(ANGLE), c(20.0)),
                          Effect(numeric=(NumericEffect("increase", VEL, c(1.0)),)), kind="event")
    report = validate(ng_task(10.0, extra_events=(sticky,)), Plan((start(0.0), stop(3.0))))
    assert not report.valid and report.kind == "event"
    assert report.time == pytest.approx(1.0, abs=1e-9)
    assert "sticky" in report.reason


def test_vals_slack_makes_a_wrap_onto_a_strict_boundary_bounce() -> None:
    # back-to-360 on (< angle 0): after back-to-zero puts the angle at exactly 0, VAL's slack
    # reads 0 < 0 as true, back-to-360 puts it at 360, back-to-zero fires again: error.
    task = ng_task(355.0, wraps=wrap_events(Comparison("<", f(ANGLE), c(0.0))))
    plan = Plan((start(0.0), stop(1.0)))
    report = validate(task, plan)
    assert not report.valid and report.kind == "event"
    assert report.time == pytest.approx(0.5, abs=1e-9)
    assert validate(task, plan, tol=EXACT).valid  # exact mathematics: no bounce


def test_uacm_fall_crosses_threshold_at_sqrt_2d_over_a() -> None:
    # From 90 deg with a = 2 deg/s^2, the angle is 90 - t^2; 45 deg at t = sqrt(45).
    task = uacm_task(90.0, acc=2.0, threshold=45.0)
    report = validate(task, Plan((observe(7.0),)))
    assert report.valid, report.reason
    (landed,) = report.events
    assert landed.name == "landed"
    assert abs(landed.time - math.sqrt(2 * 45.0 / 2.0)) < 1e-9
    traj = report.trajectory
    assert traj is not None
    assert traj.value("(angle L2 z-axis)", 3.0) == pytest.approx(81.0, abs=1e-9)
    assert traj.value("(vel L2)", 3.0) == pytest.approx(6.0, abs=1e-9)
    assert traj.value("(angle L2 z-axis)", 7.0) == pytest.approx(41.0, abs=1e-9)


def test_uacm_grab_stops_the_fall_and_the_reset_event_fires_at_once() -> None:
    task = uacm_task(90.0, acc=2.0, threshold=45.0)
    report = validate(task, Plan((TimedAction(3.0, "grab", ("L2",)), observe(7.0))))
    assert not report.valid and report.kind == "goal"  # never lands: (done) false at 7
    assert [(e.name, e.time) for e in report.events] == [("reset-speed", 3.0)]
    assert report.events[0].after_actions
    traj = report.trajectory
    assert traj is not None
    assert traj.value("(angle L2 z-axis)", 6.0) == pytest.approx(81.0, abs=1e-9)
    assert traj.value("(vel L2)", 6.0) == 0.0


def test_simulate_does_not_judge_but_records_rows_and_samples() -> None:
    task = ng_task(50.0, goal=Comparison(">", f(ANGLE), c(1000.0)))  # unreachable goal
    traj = simulate(task, Plan((start(0.0), stop(2.0))), sample_dt=0.5)
    kinds = [r.kind for r in traj.rows]
    assert kinds[0] == "init" and kinds.count("action") == 2 and kinds.count("sample") == 5
    samples = [(r.time, r.values[ANGLE]) for r in traj.rows if r.kind == "sample"]
    assert samples == [
        (0.0, 50.0), (0.5, 55.0), (1.0, 60.0), (1.5, 65.0), (2.0, 70.0)
    ]


def test_goal_reached_via_event_fact() -> None:
    task = uacm_task(50.0, acc=2.0, threshold=46.0)  # 4 deg: t = 2
    report = validate(task, Plan((observe(2.0),)))
    # The event at exactly t = 2 fires before the action at 2, so (done) holds at the end.
    assert report.valid, report.reason
    assert report.events[0].time == pytest.approx(2.0, abs=1e-9)
    assert not report.events[0].after_actions


def test_simulate_can_predict_past_the_plans_end() -> None:
    task = uacm_task(90.0, acc=2.0, threshold=45.0)
    traj = simulate(task, Plan((observe(1.0),)), extend=10.0, sample_dt=1.0)
    assert [e.name for e in traj.events] == ["landed"]  # at sqrt(45) = 6.7 s, after the end
    assert abs(traj.events[0].time - math.sqrt(45.0)) < 1e-9
    assert traj.value("(angle L2 z-axis)", 7.0) == pytest.approx(41.0, abs=1e-9)
    assert max(r.time for r in traj.rows if r.kind == "sample") == 11.0
    assert traj.final_state is not None and traj.final_state.time == 1.0


def test_division_by_zero_is_reported_not_raised() -> None:
    from artiplan.pddl.task import BinOp

    div = GroundAction("halve", (), Comparison(">", BinOp("/", f(ANGLE), f(VEL)), c(0.0)),
                       Effect(), kind="action")
    task = ng_task(10.0)
    task = type(task)(**{**task.__dict__, "actions": (*task.actions, div)})
    report = validate(task, Plan((TimedAction(1.0, "halve"),)))  # vel is 0
    assert not report.valid and report.kind == "error"
    assert "division by zero" in report.reason
