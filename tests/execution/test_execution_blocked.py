"""Rotations the robot cannot do: a blocked pair's ``connected`` fact is left out of the
problem; a rotation the world refuses is not the next plan's first one (until the chain has
moved), and planning again after a refusal that moved nothing is no re-plan."""

from __future__ import annotations

import random
from dataclasses import replace
from typing import Any

import pytest

from artiplan.encoding import EncodingOptions, make_goal
from artiplan.encoding.suite import make_task, random_pair
from artiplan.execution import LoopConfig, run_loop
from artiplan.execution.problem import build_problem
from artiplan.model import ArticulatedObject


def test_blocked_pair_is_left_out_of_the_problem() -> None:
    obj = ArticulatedObject(4)
    task = make_task(4, 1, seed=7)
    enc = EncodingOptions("ng")
    goal = make_goal(obj, task.target, "window", 1, planes=enc.planes, tolerance=2.5)
    plain = build_problem(obj, task.initial, task.target, enc, goal)
    blocked = build_problem(obj, task.initial, task.target, enc, goal,
                            blocked=frozenset({("L2", "L3")}))
    assert "(connected L2 L3)" in plain
    assert "(connected L2 L3)" not in blocked
    assert "(connected L1 L2)" in blocked and "(connected L3 L4)" in blocked


def test_refused_rotations_wait_until_the_chain_has_moved() -> None:
    from artiplan.backends import get_planner
    from artiplan.encoding import domain_pddl

    obj = ArticulatedObject(4)
    task = make_task(4, 1, seed=7)
    enc = EncodingOptions("ucm", speed_g=0.948, reach_time=3.178, refusals=True)
    goal = make_goal(obj, task.target, "window", 1, planes=enc.planes, tolerance=1.5)
    planner = get_planner("artiplan")
    first: list[str] = []
    refused: frozenset[tuple[str, str, str, str]] = frozenset()
    for _ in range(2):
        problem = build_problem(obj, task.initial, task.target, enc, goal, hands_away=True,
                                refused=refused)
        result = planner.plan(domain_pddl(obj, enc), problem, time_limit=60)
        assert result.plan is not None
        a = result.plan.actions[0]
        first.append(a.signature)
        refused = refused | {(a.args[0], a.args[1], a.args[2], a.name.split("-")[1])}
    # The refused start is not the first one any more; it stays allowed later (not blocked).
    assert first[0] != first[1]
    assert "(or (unlocked ?l2) (not (refused-increase ?l1 ?l2 ?p)))" in domain_pddl(obj, enc)
    with pytest.raises(ValueError, match="refusals=True"):
        build_problem(obj, task.initial, task.target, EncodingOptions("ucm"), goal,
                      refused=frozenset({("L2", "L3", "z-axis", "increase")}))


def test_loop_plans_around_a_refused_rotation_without_spending_a_replan() -> None:
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    failed: list[tuple[str, str, str, int]] = []
    real = world.hold_and_rotate

    def first_grasp_fails(hold: str, turn: str, plane: str, direction: int, *args: Any,
                          **kwargs: Any) -> None:
        if not failed:  # the robot refuses the first rotation it is sent to, once
            failed.append((hold, turn, plane, direction))
            raise RuntimeError(f"no collision-free grasps for {turn} (injected)")
        real(hold, turn, plane, direction, *args, **kwargs)

    world.hold_and_rotate = first_grasp_fails  # type: ignore[method-assign]
    lines: list[str] = []
    log = run_loop(world, target, LoopConfig(EncodingOptions("ng")), progress=lines.append,
                   seed=6)
    assert failed and log.refusals and not log.replans
    assert log.refusals[0]["reason"].startswith("action failed")
    hold, turn, plane, direction = failed[0]
    sign = "increase" if direction > 0 else "decrease"
    assert any(f"without starting with (start-{sign} {hold} {turn} {plane})" in line
               for line in lines)
    second = [a["action"] for a in log.plans[1]["actions"]]
    assert second and second[0] != f"(start-{sign} {hold} {turn} {plane})"
    assert log.final["replans"] == 0 and log.success


def test_plan_steps_map_each_action_once_with_its_own_stop() -> None:
    from artiplan.execution.dispatch import Observe, Rotate, Stop, Unknown, plan_steps
    from artiplan.model import ArticulatedObject
    from artiplan.semantics import Plan, TimedAction

    plan = Plan((
        TimedAction(1.44, "start-increase", ("l2", "L3", "Z-AXIS")),
        TimedAction(5.0, "stop-increase", ("L1", "L2", "z-axis")),  # another pair's stop
        TimedAction(9.44, "stop-increase", ("l2", "l3", "z-axis")),  # its own (any case)
        TimedAction(10.0, "start-decrease", ("L3", "L4", "xy-axes")),  # never stopped
        TimedAction(12.0, "dance"),
        TimedAction(13.0, "observe"),
    ))
    steps = plan_steps(plan, ArticulatedObject(4))
    assert [type(s) for s in steps] == [Rotate, Stop, Stop, Rotate, Unknown, Observe]
    first, last = steps[0], steps[3]
    assert isinstance(first, Rotate) and isinstance(last, Rotate)
    assert (first.hold, first.turn, first.plane, first.direction) == ("L2", "L3", "z-axis", 1)
    assert first.duration == pytest.approx(8.0)
    assert last.direction == -1 and last.duration is None


def test_refusals_are_dropped_when_their_pair_moves_and_free_up_to_a_budget() -> None:
    from artiplan.execution.dispatch import Rotate
    from artiplan.execution.refusals import MAX_FREE, Refusals, describe
    from artiplan.semantics import TimedAction

    obj = ArticulatedObject(4)

    def rot(hold: str, turn: str, plane: str, direction: int) -> Rotate:
        sign = "increase" if direction > 0 else "decrease"
        return Rotate(TimedAction(1.0, f"start-{sign}", (hold, turn, plane)), hold, turn,
                      plane, direction, 5.0)

    r = Refusals()
    r.refuse(rot("L2", "L3", "z-axis", 1), in_time=True)
    r.refuse(rot("L3", "L4", "xy-axes", -1), in_time=True)
    assert r.free and describe(sorted(r.refused)[0]) == "(start-increase L2 L3 z-axis)"
    r.turned(rot("L2", "L3", "z-axis", 1), obj, 9.9)  # short of CLEAR_DEG: nothing moved
    assert len(r.refused) == 2
    r.turned(rot("L3", "L4", "z-axis", 1), obj, 10.0)  # L4 moved: only L3-L4's refusal goes
    assert r.refused == {("L2", "L3", "z-axis", "increase")}
    r.refuse(rot("L1", "L2", "z-axis", 1), in_time=True)
    assert r.free  # after part of the plan moved: still planning, not a re-plan
    r.turned(rot("L1", "L2", "xy-axes", 1), obj, 12.0)  # L2 moved: every pair tip-ward of it too
    assert not r.refused
    r.relaxed = True  # a plan that ignored the refusals, refused again from here
    r.refuse(rot("L2", "L3", "z-axis", 1), in_time=True)
    assert not r.free  # the grasp choice is deterministic: a re-plan
    r.refuse(rot("L2", "L3", "z-axis", 1), in_time=True, arms_caught=True)
    assert r.free  # no arm motion found (randomised): it may go next time
    r.relaxed, r.count = False, MAX_FREE
    r.refuse(rot("L2", "L3", "z-axis", 1), in_time=True)
    assert not r.free  # the free ones are used up
    r.count = 0
    r.refuse(rot("L2", "L3", "z-axis", 1), in_time=False)
    assert not r.free


def test_arms_caught_go_home_and_their_refusals_are_tried_again() -> None:
    from artiplan.execution.dispatch import Rotate
    from artiplan.execution.refusals import MAX_ESCAPES, Refusals
    from artiplan.semantics import TimedAction

    def rot(hold: str, turn: str, direction: int) -> Rotate:
        sign = "increase" if direction > 0 else "decrease"
        return Rotate(TimedAction(1.0, f"start-{sign}", (hold, turn, "z-axis")), hold, turn,
                      "z-axis", direction, 5.0)

    r = Refusals()
    r.refuse(rot("L2", "L3", 1), in_time=True)  # no collision-free grasp pair: stays refused
    assert not r.stuck
    r.refuse(rot("L1", "L2", 1), in_time=True, arms_caught=True)  # no arm motion found
    assert r.stuck
    r.escaped(moved=True)
    assert not r.stuck and r.escapes == 1
    assert r.refused == {("L2", "L3", "z-axis", "increase")}  # the motion refusal is gone
    r.refuse(rot("L1", "L2", -1), in_time=True, arms_caught=True)
    r.escaped(moved=False)  # no path home: the refusal stays
    assert ("L1", "L2", "z-axis", "decrease") in r.refused
    r.refuse(rot("L1", "L2", 1), in_time=True, arms_caught=True)
    assert not r.stuck  # no way home from here: not tried again before something turned
    r.turned(rot("L2", "L3", 1), ArticulatedObject(4), 10.0)
    r.refuse(rot("L1", "L2", 1), in_time=True, arms_caught=True)
    assert r.stuck
    r.escapes = MAX_ESCAPES
    r.refuse(rot("L1", "L2", 1), in_time=True, arms_caught=True)
    assert not r.stuck  # the run's escapes are used up


def test_the_world_sends_caught_arms_home_by_a_planned_motion() -> None:
    import mujoco
    import numpy as np

    from artiplan.model import Configuration
    from artiplan.world import make_world

    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(ArticulatedObject(4), conf, hands="baxter")
    hands: Any = world.hands
    assert world.arms_home() is False  # home already: nothing moves
    q = hands.home["right"] + np.array([0.3, -0.25, 0.2, 0.35, 0.0, 0.2, 0.0])
    world.data.qpos[hands._q["right"]] = q
    hands._target_q["right"] = q.copy()
    mujoco.mj_forward(world.model, world.data)
    t, motions = world.time, len(hands.checker.stats)
    assert world.arms_home() is True
    assert world.time > t  # in simulated time, the world running
    assert len(hands.checker.stats) > motions and hands.checker.stats[-1].ok  # planned
    assert float(np.abs(world.data.qpos[hands._q["right"]] - hands.home["right"]).max()) < 0.05
    virtual = make_world(ArticulatedObject(4), conf, hands="virtual")
    assert virtual.arms_home() is False  # no arms to move


def test_a_plan_around_refusals_longer_than_the_time_left_is_replaced() -> None:
    from artiplan.execution.loop import ClosedLoop
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    loop = ClosedLoop(world, target, LoopConfig(EncodingOptions("ng"), max_time=30.0), None, 6,
                      None)
    real = loop.planner.plan
    asked: list[bool] = []

    def stretched(domain: str, problem: str, **kw: Any) -> Any:
        result = real(domain, problem, **kw)
        asked.append("refused-" in problem)
        if "refused-" in problem and result.plan is not None:  # around the refusal: too long
            result.plan = replace(result.plan, actions=tuple(
                replace(a, time=a.time * 100.0) for a in result.plan.actions))
        return result

    loop.planner.plan = stretched  # type: ignore[method-assign]
    lines: list[str] = []
    loop._say = lines.append
    loop.refusals.refused = frozenset({("L1", "L2", "z-axis", "increase")})
    result = loop._solve(init)
    assert asked == [True, False]  # around the refusal first, then without it
    span = max(result.plan.makespan, result.plan.end or 0.0)
    assert span <= 30.0
    assert any("planning again without the refusals" in line for line in lines)


def test_no_plan_with_the_gravity_model_tries_the_fallback_model_before_giving_up() -> None:
    from artiplan.semantics.results import PlanResult, PlanStatus
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    from artiplan.execution.loop import ClosedLoop

    cfg = LoopConfig(EncodingOptions("ucm", speed_g=0.5), max_turn_deg=None)  # one try each
    loop = ClosedLoop(world, target, cfg, None, 6, None)
    real = loop.planner.plan
    models: list[str] = []

    def ucm_times_out(domain: str, problem: str, **kw: Any) -> Any:
        models.append("ucm" if "artiplan-ucm" in domain else "ng")
        if models[-1] == "ucm":
            return PlanResult(PlanStatus.TIMEOUT, message="time limit (injected)")
        return real(domain, problem, **kw)

    loop.planner.plan = ucm_times_out  # type: ignore[method-assign]
    log = loop.run()
    assert models[:2] == ["ucm", "ng"]  # one plan: the fallback model's, from then on
    assert log.plans[0]["status"] == "solved" and log.plans[0]["model"] == "ng"
    assert not log.replans and not log.refusals and log.success


@pytest.mark.parametrize("scope", ["run", "plan"])
def test_the_fallback_model_stays_for_the_run_or_makes_only_the_plan_it_was_needed_for(
        scope: str) -> None:
    """UCM finds no plan once: NG makes that plan; the next plan is NG's again with the scope
    ``run`` and UCM's own with ``plan``."""
    from artiplan.semantics.results import PlanResult, PlanStatus
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    from artiplan.execution.loop import ClosedLoop

    cfg = LoopConfig(EncodingOptions("ucm", speed_g=0.5), max_turn_deg=None,
                     fallback_scope=scope)
    loop = ClosedLoop(world, target, cfg, None, 6, None)
    real = loop.planner.plan
    models: list[str] = []

    def ucm_times_out_once(domain: str, problem: str, **kw: Any) -> Any:
        models.append("ucm" if "artiplan-ucm" in domain else "ng")
        if models == ["ucm"]:
            return PlanResult(PlanStatus.TIMEOUT, message="time limit (injected)")
        return real(domain, problem, **kw)

    loop.planner.plan = ucm_times_out_once  # type: ignore[method-assign]
    assert loop._plan("initial", counted=False) is not None
    assert loop._plan("again", counted=False) is not None
    assert [p["model"] for p in loop.log.plans] == ["ng", "ng" if scope == "run" else "ucm"]
    assert models == ["ucm", "ng", "ng" if scope == "run" else "ucm"]


def test_an_unknown_fallback_scope_is_refused() -> None:
    with pytest.raises(ValueError, match="fallback_scope"):
        LoopConfig(fallback_scope="task")


def test_turns_between_separate_a_link_from_what_its_grasps_met() -> None:
    from artiplan.encoding.problem import turns_between

    assert list(turns_between(4, frozenset({1}))) == [2, 3, 4]  # the scene: L4 itself moves
    assert list(turns_between(3, frozenset({5}))) == [4, 5]  # L5 folded back beside L3
    assert list(turns_between(4, frozenset({2, 5}))) == [3, 4, 5]
    assert list(turns_between(2, frozenset({1}))) == [2]


def _plan(obj: ArticulatedObject, task: Any, enc: EncodingOptions,
          **around: Any) -> list[tuple[float, str]]:
    from artiplan.backends import get_planner
    from artiplan.encoding import domain_pddl

    goal = make_goal(obj, task.target, "window", 1, planes=enc.planes, tolerance=1.5)
    problem = build_problem(obj, task.initial, task.target, enc, goal, hands_away=True,
                            **around)
    result = get_planner("artiplan").plan(domain_pddl(obj, enc), problem, time_limit=60)
    assert result.plan is not None
    return [(a.time, a.signature) for a in result.plan.actions]


def test_an_ungraspable_link_is_grasped_only_after_a_turn_that_moves_it() -> None:
    """L3 could not be turned (its grasps met the scene): the plan first turns L2 by
    CLEAR_FAR_DEG or more (which moves L3), and only then grasps L3 to turn it."""
    from artiplan.encoding.domain import CLEAR_FAR_DEG

    obj = ArticulatedObject(4)
    task = make_task(4, 1, seed=7)
    enc = EncodingOptions("ucm", speed_g=0.948, reach_time=3.178, refusals=True)
    free = _plan(obj, task, enc)
    assert any(" L2 L3 " in s for _, s in free)  # without the refusal, L3 is turned
    plan = _plan(obj, task, enc, ungraspable=frozenset({("L3", "turn", frozenset({1}))}))
    first = next(k for k, (_, s) in enumerate(plan) if s.startswith("(start") and " L2 L3 " in s)
    before = plan[:first]
    starts = [(t, s) for t, s in before if s.startswith("(start-")]
    assert starts and all(" L1 L2 " in s for _, s in starts)  # only L2 turns (it moves L3)
    stop = next(t for t, s in before if s.startswith("(stop-"))
    assert (stop - starts[0][0]) * enc.speed_i >= CLEAR_FAR_DEG - 1e-6


def test_a_tiny_turn_does_not_unlock_a_refusal(tmp_path: Any) -> None:
    """The start (L2 L3 xy-axes, increase) refused: a turn of L2 (which moves the pair)
    unlocks it only once it has gone CLEAR_DEG. Measured before: plans unlocked refusals with
    1 ms turns that moved nothing, and the robot refused the same grasps again."""
    from artiplan.encoding import domain_pddl
    from artiplan.encoding.domain import CLEAR_DEG
    from artiplan.pddl import load_task
    from artiplan.semantics import validate
    from artiplan.semantics.plan_io import parse_plan

    obj = ArticulatedObject(4)
    task = make_task(4, 1, seed=7)
    enc = EncodingOptions("ng", reach_time=1.0, refusals=True)
    goal = make_goal(obj, task.target, "window", 1, planes=enc.planes, tolerance=1.5)
    (tmp_path / "d.pddl").write_text(domain_pddl(obj, enc))
    (tmp_path / "p.pddl").write_text(build_problem(
        obj, task.initial, task.target, enc, goal, hands_away=True,
        refused=frozenset({("L2", "L3", "xy-axes", "increase")})))
    pddl = load_task(tmp_path / "d.pddl", tmp_path / "p.pddl")
    turn = CLEAR_DEG / enc.speed_i  # [s]
    for length, unlocked in ((0.01, False), (0.9 * turn, False), (1.01 * turn, True)):
        plan = parse_plan(f"1.01: (start-increase L1 L2 z-axis)\n"
                          f"{1.01 + length:.6f}: (stop-increase L1 L2 z-axis)\n"
                          f"{2.02 + length:.6f}: (start-increase L2 L3 xy-axes)\n")
        report = validate(pddl, plan)
        refused_at_start = report.kind == "precondition" and report.happening is not None \
            and report.time == pytest.approx(2.02 + length, abs=1e-3)
        assert refused_at_start != unlocked, (length, report.summary())


def test_refusals_forget_an_ungraspable_link_once_a_turn_separates_it() -> None:
    from artiplan.execution.dispatch import Rotate
    from artiplan.execution.refusals import Refusals
    from artiplan.semantics import TimedAction

    obj = ArticulatedObject(6)

    def rot(hold: str, turn: str) -> Rotate:
        return Rotate(TimedAction(1.0, "start-increase", (hold, turn, "z-axis")), hold, turn,
                      "z-axis", 1, 5.0)

    r = Refusals()
    r.refuse(rot("L2", "L3"), in_time=True, blocked=(("L3", "turn", frozenset({5})),))
    assert r.ungraspable == {("L3", "turn", frozenset({5}))}
    r.turned(rot("L1", "L2"), obj, 40.0)  # moves L3 and L5 together: still blocked
    assert r.ungraspable
    r.turned(rot("L4", "L5"), obj, 20.0)  # L5 turns away from L3, not yet far enough
    assert r.ungraspable
    r.turned(rot("L4", "L5"), obj, 25.0)  # CLEAR_FAR_DEG: the fold may have opened
    assert not r.ungraspable


def test_refusals_for_want_of_an_arm_motion_are_ignored_before_the_others() -> None:
    """No plan around every refusal: the next try ignores only those refused for want of an
    arm motion (randomised, free when refused again), keeping the grasps' and turns' refusals
    (they would come again from here); only then all of them."""
    from artiplan.execution.loop import ClosedLoop
    from artiplan.semantics.results import PlanResult, PlanStatus
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    loop = ClosedLoop(world, target, LoopConfig(EncodingOptions("ng"), max_turn_deg=None,
                                                fallback_model=None), None, 6, None)
    real = loop.planner.plan
    asked: list[tuple[bool, bool]] = []
    grasp, motion = ("L2", "L3", "z-axis", "increase"), ("L1", "L2", "z-axis", "decrease")

    def picky(domain: str, problem: str, **kw: Any) -> Any:
        around = ("(refused-increase L2 L3 z-axis)" in problem,
                  "(refused-decrease L1 L2 z-axis)" in problem)
        asked.append(around)
        if around[1]:  # no plan around the arm-motion refusal (injected)
            return PlanResult(PlanStatus.NO_PLAN, message="no plan (injected)")
        return real(domain, problem, **kw)

    loop.planner.plan = picky  # type: ignore[method-assign]
    loop.refusals.refused = frozenset({grasp, motion})
    loop.refusals.caught = frozenset({motion})
    result = loop._solve(init)
    assert asked == [(True, True), (True, False)]
    assert result.plan is not None and loop.refusals.relaxed
    asked.clear()
    loop.refusals.caught = frozenset()  # both refused for their grasps: all at once
    loop._solve(init)
    assert asked == [(True, True), (False, False)]
    asked.clear()
    loop.refusals.refused = loop.refusals.caught = frozenset()
    loop._solve(init)
    assert asked == [(False, False)] and not loop.refusals.relaxed


def test_a_rotation_refused_again_from_the_same_state_lets_the_chain_settle_first() -> None:
    """A dead end: a plan that had to ignore the refusals starts with a rotation refused from
    this very state, and its grasps refuse it again. The hands let go for WAIT_S (the chain
    settles under gravity) and the same planning goes on without spending the budget, at
    most MAX_WAITS times a run (then it waits and spends it); a motion not found
    (randomised) needs no wait."""
    from artiplan.execution.dispatch import Rotate
    from artiplan.execution.loop import ClosedLoop
    from artiplan.execution.refusals import MAX_WAITS, WAIT_S
    from artiplan.semantics import TimedAction
    from artiplan.world import make_world

    step = Rotate(TimedAction(1.0, "start-increase", ("L2", "L3", "z-axis")), "L2", "L3",
                  "z-axis", 1, 5.0)
    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    loop = ClosedLoop(world, target, LoopConfig(EncodingOptions("ng")), None, 6, None)
    r = loop.refusals
    r.refuse(step, in_time=True)  # first refusal: planned around, no wait
    assert r.free and not r.waiting
    r.relaxed = True  # no plan around it: the plan ignoring it starts with it again
    r.refuse(step, in_time=True, arms_caught=True)
    assert r.free and not r.waiting  # no arm motion found: may go as it is
    for _ in range(MAX_WAITS):
        r.relaxed = True  # (each new plan says whether it ignored the refusals)
        r.refuse(step, in_time=True)
        assert r.free and r.waiting
        t = world.time
        loop._plan("action failed", counted=False)
        assert world.time >= t + WAIT_S - 0.01 and not r.waiting
        assert loop.log.happenings[-1]["action"] == "(wait)"
    r.relaxed = True
    r.refuse(step, in_time=True)
    assert r.waiting and not r.free  # the free waits are used up: a re-plan, after a wait
    t = world.time
    loop._plan("action failed", counted=True)
    assert world.time >= t + WAIT_S - 0.01 and not r.waiting
    r.relaxed = True
    r.refuse(step, in_time=False)  # no time left: neither a wait nor a free plan
    assert not r.waiting and not r.free


def test_no_arm_motion_and_no_way_home_is_a_dead_end_too() -> None:
    """Refused for want of an arm motion, with the arms' way home not found either: from the
    same state nothing changes until time passes (measured: 28 such refusals in a row at one
    instant of a 4-link run), so the hands let go and the chain settles first; after the
    wait a way home may be found again."""
    from artiplan.execution.dispatch import Rotate
    from artiplan.execution.loop import ClosedLoop
    from artiplan.execution.refusals import MAX_ESCAPES, WAIT_S
    from artiplan.semantics import TimedAction
    from artiplan.world import make_world

    step = Rotate(TimedAction(1.0, "start-decrease", ("L2", "L3", "z-axis")), "L2", "L3",
                  "z-axis", -1, 5.0)
    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    loop = ClosedLoop(world, target, LoopConfig(EncodingOptions("ng")), None, 6, None)
    r = loop.refusals
    r.refuse(step, in_time=True, arms_caught=True)
    assert r.free and r.stuck and not r.waiting  # first: the arms go home
    r.escaped(moved=False)
    assert r.homeless
    r.relaxed = True
    r.refuse(step, in_time=True, arms_caught=True)
    assert r.free and not r.stuck and r.waiting
    t = world.time
    loop._plan("action failed", counted=False)
    assert world.time >= t + WAIT_S - 0.01 and not r.waiting and not r.homeless
    r.relaxed = True
    r.refuse(step, in_time=True, arms_caught=True)  # a way home may be tried again first
    assert r.stuck and not r.waiting
    r.escapes = MAX_ESCAPES  # no escape left: a dead end again, though a way home may exist
    r.relaxed = True
    r.refuse(step, in_time=True, arms_caught=True)
    assert not r.stuck and r.waiting


def test_a_turn_its_link_does_not_follow_is_refused_without_spending_a_replan() -> None:
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    slowed: list[tuple[str, str, str, int]] = []
    real = world.hold_and_rotate

    def first_turn_stalls(hold: str, turn: str, plane: str, direction: int,
                          speed_deg_s: float = 10.0, *args: Any, **kwargs: Any) -> None:
        if not slowed:  # the first rotation's link follows its hand at a tenth of the speed
            slowed.append((hold, turn, plane, direction))
            speed_deg_s *= 0.1
        real(hold, turn, plane, direction, speed_deg_s, *args, **kwargs)

    world.hold_and_rotate = first_turn_stalls  # type: ignore[method-assign]
    log = run_loop(world, target, LoopConfig(EncodingOptions("ng"), stall_deg=6.0), seed=6)
    hold, turn, plane, direction = slowed[0]
    start = f"(start-{'increase' if direction > 0 else 'decrease'} {hold} {turn} {plane})"
    stalled = [r for r in log.refusals if "stalled" in r["reason"]]
    assert stalled and stalled[0]["reason"].startswith(f"{turn} off the prediction")
    assert f"{start} stalled" in stalled[0]["reason"]
    assert not any("stalled" in r["reason"] for r in log.replans)
    # The next plan does not start with the stalled rotation (its pair has not moved enough).
    second = [a["action"] for a in log.plans[1]["actions"]]
    assert second and second[0] != start
    assert log.success

    # Off (stall_deg None, the default): the same lag is an ordinary re-plan.
    world = make_world(obj, init, hands="virtual", seed=6)
    real = world.hold_and_rotate
    slowed.clear()
    world.hold_and_rotate = first_turn_stalls  # type: ignore[method-assign]
    log = run_loop(world, target, LoopConfig(EncodingOptions("ng"), stall_deg=None), seed=6)
    assert not any("stalled" in r["reason"] for r in log.refusals + log.replans)
    assert log.replans and log.replans[0]["reason"].startswith(f"{turn} off the prediction")


def test_stall_deg_must_be_positive() -> None:
    with pytest.raises(ValueError, match="stall_deg"):
        LoopConfig(stall_deg=0.0)


def test_refusals_are_tried_again_once_the_percepts_show_the_chain_moved_away() -> None:
    """Task 20 with the push (session 25): L2's own turn was refused (its grasps met the
    fixture), and L3 (met L2, folded back on it) could not be grasped; in the dead-end waits
    L2 fell 30 deg with L3 folded on it. L2's turn may be tried again and L3 still not; a
    new refusal measures from then."""
    from artiplan.execution.dispatch import Rotate
    from artiplan.execution.refusals import MOVED_DEG, Refusals
    from artiplan.model import Configuration
    from artiplan.semantics import TimedAction

    def rot(hold: str, turn: str) -> Rotate:
        return Rotate(TimedAction(1.0, "start-increase", (hold, turn, "z-axis")), hold, turn,
                      "z-axis", 1, 5.0)

    obj = ArticulatedObject(4)
    l2 = ("L2", "turn", frozenset({1}))
    l3 = ("L3", "turn", frozenset({2}))
    l3_held = ("L3", "hold", frozenset({1, 2}))  # met L2 and the fixture
    pair = ("L1", "L2", "z-axis", "increase")
    r = Refusals()
    r.refuse(rot("L2", "L3"), in_time=True, blocked=(l3,))
    r.refuse(rot("L3", "L4"), in_time=True, blocked=(l3_held,))
    r.refuse(rot("L1", "L2"), in_time=True, blocked=(l2,))
    then = Configuration((45.0, 270.0, 90.0, 20.0), (43.0, 164.0, 26.0, 70.0))
    assert r.settled(then, obj) == ([], []) and r.ungraspable == {l2, l3, l3_held}
    a_little = Configuration((45.0, 270.0, 90.0, 20.0),
                             (43.0, 164.0 - 0.9 * MOVED_DEG, 26.0 + 0.9 * MOVED_DEG, 70.0))
    assert r.settled(a_little, obj) == ([], [])
    fell = Configuration((45.0, 270.0, 90.0, 20.0), (43.0, 134.0, 56.0, 70.0))
    pairs, links = r.settled(fell, obj)
    # L3 is still folded on L2, but it has moved away from the fixture
    assert set(links) == {l2, l3_held} and r.ungraspable == {l3}
    assert set(pairs) == {pair, ("L2", "L3", "z-axis", "increase")}  # L2 and L3 moved
    assert r.refused == {("L3", "L4", "z-axis", "increase")}  # L4 has not
    assert set(r.seen) == {l3, ("L3", "L4", "z-axis", "increase")}
    r.refuse(rot("L1", "L2"), in_time=True, blocked=(l2,))  # refused again: measured from now
    assert r.settled(fell, obj) == ([], []) and r.ungraspable == {l2, l3}
    assert pair in r.refused
