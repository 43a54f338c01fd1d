"""A grasp that fails (e.g. out of the arm's reach) is not planned again at once: the next
problem leaves that pair's ``connected`` fact out."""

from __future__ import annotations

import random
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


def test_loop_replans_around_a_failed_grasp() -> None:
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(6))
    world = make_world(obj, init, hands="virtual", seed=6)
    failed: list[tuple[str, str]] = []
    real = world.hold_and_rotate

    def first_grasp_fails(hold: str, turn: str, *args: Any, **kwargs: Any) -> None:
        if not failed:  # the robot cannot take the first grasp it is sent to, once
            failed.append((hold, turn))
            raise RuntimeError(f"cannot reach {turn} (injected)")
        real(hold, turn, *args, **kwargs)

    world.hold_and_rotate = first_grasp_fails  # type: ignore[method-assign]
    lines: list[str] = []
    log = run_loop(world, target, LoopConfig(EncodingOptions("ng")), progress=lines.append,
                   seed=6)
    assert failed and log.replans
    assert log.replans[0]["reason"].startswith("action failed")
    hold, turn = failed[0]
    # The re-plan does without the failed grasp (moving L3 by turning L2 instead), and the
    # goal is still reached.
    assert any(f"without grasping {hold}+{turn}" in line for line in lines)
    second = [a["action"] for a in log.plans[1]["actions"]]
    assert second and not any(f" {hold} {turn} " in a for a in second)
    assert log.success


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
