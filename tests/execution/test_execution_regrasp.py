"""A turn the arms stop short is resumed by a re-grasp (the plan's clock waits, no re-plan);
every turn is aligned on the perceived link when it starts."""

from __future__ import annotations

import random
from typing import Any

from artiplan.encoding import EncodingOptions
from artiplan.encoding.suite import random_pair
from artiplan.execution import LoopConfig, run_loop
from artiplan.execution.dispatch import Rotate
from artiplan.execution.regrasp import MAX_LOST_DEG, Resume, behind_deg
from artiplan.model import ArticulatedObject, Configuration
from artiplan.model.angles import signed_delta_deg
from artiplan.semantics import TimedAction


def test_loop_resumes_a_turn_stopped_short_and_reaches_the_goal() -> None:
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    real = world.hold_and_rotate
    calls: list[float | None] = []

    def first_turn_stops_early(*args: Any, **kwargs: Any) -> None:
        # The first grasp pair can turn only 10 deg (as Baxter's arms near the fixture).
        world.hands.turn_limit = (10.0, "injected") if not calls else None  # type: ignore[attr-defined]
        calls.append(kwargs.get("extent_deg"))
        real(*args, **kwargs)

    world.hold_and_rotate = first_turn_stops_early  # type: ignore[method-assign]
    log = run_loop(world, target, LoopConfig(EncodingOptions("ng")), seed=6)
    resumed = [h for h in log.happenings if h["action"].endswith("resumed")]
    assert resumed and resumed[0]["ok"] and resumed[0]["did"].startswith("re-grasp")
    first = calls[0]
    assert first is not None and first > 11.0
    # The re-grasp asks for the rest of the planned turn, not the whole of it again.
    assert calls[1] is not None and abs(calls[1] - (first - 10.0)) < 1.0
    assert not log.replans and log.success


def test_resume_remaining_and_lost() -> None:
    step = Rotate(TimedAction(2.0, "start-increase", ("L2", "L3", "z-axis")), "L2", "L3",
                  "z-axis", 1, 8.0)
    r = Resume(step, 10.0, due=5.0)
    assert r.remaining(t0=1.0, now=5.0) == 60.0  # its stop at 1 + 2 + 8 = 11 s
    pred = Configuration((0.0, 0.0, 0.0), (0.0, 90.0, 120.0))
    behind = Configuration((0.0, 0.0, 0.0), (0.0, 90.0, 117.0))
    ahead = Configuration((0.0, 0.0, 0.0), (0.0, 90.0, 124.0))
    far = Configuration((0.0, 0.0, 0.0), (0.0, 90.0, 60.0))
    assert abs(behind_deg(step, pred, behind, 3) - 3.0) < 1e-9
    assert abs(behind_deg(step, pred, ahead, 3) + 4.0) < 1e-9
    assert behind_deg(step, pred, far, 3) == MAX_LOST_DEG
    # About the vertical, a link near the pole has no azimuth to align on.
    spin = Rotate(step.action, "L2", "L3", "xy-axes", 1, 8.0)
    pole = Configuration((0.0, 0.0, 30.0), (0.0, 90.0, 5.0))
    near = Configuration((0.0, 0.0, 20.0), (0.0, 90.0, 5.0))
    assert behind_deg(spin, pole, near, 3) == 0.0
    level = Configuration((0.0, 0.0, 30.0), (0.0, 90.0, 90.0))
    assert abs(behind_deg(spin, level, Configuration((0.0, 0.0, 20.0), (0.0, 90.0, 90.0)), 3)
               - 10.0) < 1e-9


def _seed7_plan() -> tuple[ArticulatedObject, Any, Any]:
    """(object, task, planner result) of seeded 4-link task 1 (seed 7) planned in UCM: a
    vertical turn the plan stops, then a turn about the vertical to the plan's end."""
    from artiplan.backends import get_planner
    from artiplan.encoding import domain_pddl, make_goal
    from artiplan.encoding.suite import make_task
    from artiplan.execution.problem import build_problem

    obj = ArticulatedObject(4)
    task = make_task(4, 1, seed=7)
    enc = EncodingOptions("ucm", speed_g=0.948)
    goal = make_goal(obj, task.target, "window", 1, planes=enc.planes, tolerance=1.5)
    result = get_planner("artiplan").plan(
        domain_pddl(obj, enc), build_problem(obj, task.initial, task.target, enc, goal),
        time_limit=60)
    return obj, task, result


def test_a_fade_predicts_a_link_where_it_was_seen_until_the_turn_catches_up() -> None:
    from artiplan.execution.predict import Prediction

    obj, task, result = _seed7_plan()
    assert result.trajectory is not None
    pred = Prediction(obj, result.trajectory, 2.0, task.initial)
    plain = [pred.at(t) for t in (3.0, 4.0, 5.0, 6.0)]
    pred.fade({3: -8.0, 4: -8.0}, "z-axis", 3.0, 5.0)
    faded = [pred.at(t) for t in (3.0, 4.0, 5.0, 6.0)]
    for (a, b), off in zip(zip(plain, faded, strict=True), (-8.0, -4.0, 0.0, 0.0), strict=True):
        for i in (3, 4):
            assert abs(signed_delta_deg(a.angle(i, "z-axis"), b.angle(i, "z-axis")) - off) < 1e-9
        assert a.theta == b.theta and a.gamma[:2] == b.gamma[:2]
    pred.fade({2: 1.0}, "xy-axes", 6.0, 7.0)  # the expired fade is dropped
    assert [f.index for f in pred.fades] == [2]


def test_an_offset_a_turn_ahead_aligns_is_not_judged() -> None:
    from artiplan.execution.regrasp import POLE_DEG, aligned_ahead

    predicted = Configuration((10.0, 20.0, 30.0), (90.0, 100.0, 110.0))
    seen = Configuration((10.0, 31.0, 30.0 + MAX_LOST_DEG + 1.0), (90.0, 92.0, 110.0))
    # L2: ahead by 11 deg of a 30 deg increase on xy, 8 deg of a 20 deg decrease on z.
    ahead = {(2, "xy-axes"): (1, 30.0), (2, "z-axis"): (-1, 20.0), (3, "xy-axes"): (-1, 90.0)}
    judged, notes = aligned_ahead(predicted, seen, ahead)
    assert judged.angle(2, "xy-axes") == 31.0 and judged.angle(2, "z-axis") == 92.0
    assert notes == ["L2 xy-axes +11.0", "L2 z-axis -8.0"]
    # L3 is behind its decrease by more than MAX_LOST_DEG: judged against the plan.
    assert judged.angle(3, "xy-axes") == 30.0
    # Ahead by more than the turn's extent: the turn would have to go back, so judged.
    short = {(2, "xy-axes"): (1, 10.0)}
    assert aligned_ahead(predicted, seen, short)[0].angle(2, "xy-axes") == 20.0
    # Behind by less than MAX_LOST_DEG, whatever the extent: the turn goes on longer.
    assert aligned_ahead(predicted, seen, {(2, "xy-axes"): (-1, 5.0)})[0].angle(
        2, "xy-axes") == 31.0
    # Without a turn ahead nothing passes.
    assert aligned_ahead(predicted, seen, {}) == (predicted, [])
    # Near the vertical an azimuth is not aligned (behind_deg), so it is judged.
    pole = Configuration((10.0, 20.0, 30.0), (90.0, POLE_DEG / 2, 110.0))
    near = Configuration((10.0, 31.0, 30.0), (90.0, POLE_DEG / 2, 110.0))
    assert aligned_ahead(pole, near, ahead)[0].angle(2, "xy-axes") == 20.0


def test_a_small_push_on_a_link_the_plan_turns_later_needs_no_re_plan() -> None:
    """A 10 deg push on L3's vertical angle before the plan's own vertical turn of L3: the
    turn's alignment takes it, so the loop reaches the goal without re-planning (with every
    offset judged, the same push re-plans)."""
    from artiplan.execution import Intervention
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(11))
    push = Intervention(0.3, "L3", "z-axis", 10.0)
    runs = {}
    for ahead in (True, False):
        world = make_world(obj, init, hands="virtual", seed=11)
        cfg = LoopConfig(EncodingOptions("ng"), interventions=(push,), monitor_ahead=ahead)
        runs[ahead] = run_loop(world, target, cfg, seed=11)
    assert runs[True].success and not runs[True].replans
    assert any("aligned_ahead" in s for s in runs[True].samples)
    assert runs[False].replans and "L3 off the prediction" in runs[False].replans[0]["reason"]


def test_a_held_link_ahead_of_its_turn_is_aligned_up_to_what_is_left_of_the_turn() -> None:
    """With ``align_ahead``, at the grasp a link ahead of its turn is aligned as far as the
    turn has left (to its stop, or to the plan's end for a turn the plan never stops; less
    MIN_REMAINING_DEG), beyond MAX_LOST_DEG: the plan's clock moves on by that much and the
    prediction then has the link where it is seen. Behind stays capped at MAX_LOST_DEG, and
    without the option ahead is too."""
    from artiplan.execution.dispatch import plan_steps
    from artiplan.execution.predict import Prediction
    from artiplan.execution.regrasp import MIN_REMAINING_DEG, align
    from artiplan.world import make_world

    obj, task, result = _seed7_plan()
    assert result.plan is not None and result.trajectory is not None
    trajectory = result.trajectory
    assert trajectory.end is not None
    speed = 10.0
    turns = [s for s in plan_steps(result.plan, obj) if isinstance(s, Rotate)]
    # One the plan stops and one it never stops (_seed7_plan).
    assert {s.duration is None for s in turns} == {True, False}
    for step in turns:
        stop = step.action.time + (step.duration if step.duration is not None
                                   else trajectory.end)
        extent = speed * (stop - step.action.time)
        assert extent > MAX_LOST_DEG + 10.0, "a turn too short to test on"
        j = obj.index(step.turn)

        def aligned(offset: float, ahead_to_end: bool = True, step: Rotate = step, j: int = j
                    ) -> tuple[float, Prediction, Configuration]:
            """(align's answer, the prediction after it, what was set): the world at the
            turn's start, the link ``offset`` deg ahead of the prediction along the turn."""
            pred = Prediction(obj, trajectory, -float(step.action.time), task.initial)
            at = pred.at(0.0)
            angles = list(at.theta if step.plane == "xy-axes" else at.gamma)
            angles[j - 1] = (angles[j - 1] + step.direction * offset) % 360.0
            conf = (Configuration(tuple(angles), at.gamma) if step.plane == "xy-axes"
                    else Configuration(at.theta, tuple(angles)))
            return align(make_world(obj, conf), step, pred, speed, ahead_to_end), pred, conf

        # The default (LoopConfig.align_ahead off): ahead too only up to MAX_LOST_DEG.
        assert aligned(MAX_LOST_DEG + 10.0, ahead_to_end=False)[0] == -MAX_LOST_DEG

        far = min(MAX_LOST_DEG + 10.0, extent - MIN_REMAINING_DEG - 2.0)
        behind, pred, conf = aligned(far)
        assert abs(behind + far) < 1.5, step  # all of it, not only MAX_LOST_DEG
        assert abs(signed_delta_deg(pred.at(0.0).angle(j, step.plane),
                                    conf.angle(j, step.plane))) < 1.5
        behind, _, _ = aligned(-(MAX_LOST_DEG + 10.0))
        assert behind == MAX_LOST_DEG
