"""Baxter's chosen grasps keep the arms clear of the torso, the other arm and the scene."""

from __future__ import annotations

import random

import mujoco
import pytest

from artiplan.model import ArticulatedObject, Configuration, random_configuration
from artiplan.world import make_world
from artiplan.world.collision import arm_contacts, arm_geoms, clearance


def test_clearance_sees_a_collision_and_ignores_the_mounted_shoulder() -> None:
    obj = ArticulatedObject(4)
    world = make_world(obj, hands="baxter")
    geoms = arm_geoms(world.model, "left", list(obj.links))
    assert geoms.arm and geoms.torso and geoms.other and geoms.gripper
    # At home the arms are clear (the shoulder sits on the torso: that pair is not checked).
    assert clearance(world.model, world.data, geoms)[0] > 0.0
    # Fold the left elbow fully (e1 2.5 rad): the hand goes into the torso.
    q = world.hands._q["left"]
    world.data.qpos[q[:4]] = (0.5, 0.5, 0.0, 2.5)
    mujoco.mj_kinematics(world.model, world.data)
    dist, pair = clearance(world.model, world.data, geoms)
    assert dist < 0.0 and "base_link_col" in pair, pair  # the torso
    assert arm_contacts(world.model, world.data, geoms) > 0


@pytest.mark.slow
@pytest.mark.parametrize(("k", "plane"), [(2, "z-axis"), (3, "xy-axes")])
def test_baxter_grasps_are_collision_free_on_four_links(k: int, plane: str) -> None:
    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter", preset="stiff", avoid_collisions=True)
    world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, 1, 10.0)
    for hand in ("left", "right"):
        geoms = arm_geoms(world.model, hand, list(obj.links))
        dist, pair = clearance(world.model, world.data, geoms, world.hands.held(hand), False)
        assert dist > 0.0, f"{hand}: {pair} {dist:.3f} m"
        assert arm_contacts(world.model, world.data, geoms) == 0


@pytest.mark.slow
def test_baxter_retreats_after_release_in_simulated_time() -> None:
    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter", preset="stiff")
    world.hold_and_rotate("L2", "L3", "z-axis", 1, 10.0)
    world.run_until(0.5)
    hands = world.hands
    grasp_points = {h: world.data.xpos[hands._hand[h]].copy() for h in ("left", "right")}
    world.stop(release=True)
    t0 = world.time
    hands.retreat(["left", "right"], world.step, distance=0.1, duration_s=0.5)
    # At least 0.5 s of motion (more if Baxter's joint limits need it) + 0.2 s settling.
    assert t0 + 0.7 - 0.01 <= world.time < t0 + 2.0
    for h in ("left", "right"):
        assert hands.held(h) is None
        moved = float(((world.data.xpos[hands._hand[h]] - grasp_points[h]) ** 2).sum() ** 0.5)
        assert 0.07 < moved < 0.13, (h, moved)


@pytest.mark.slow
@pytest.mark.ci
def test_baxter_arms_stay_clear_over_a_rotation_that_collided_before() -> None:
    """4 links, seed 6 of benchmarks/world_collision.py: hold L2, rotate L3 by +30 deg on
    xy-axes. With the grasps chosen by clearance at the grasp only (commit e27f562), an arm
    ended 6 cm inside the torso's hull after the turn; scoring the turned poses too (the
    holding arm at its grasp) keeps both arms clear."""
    rng = random.Random(6)
    conf = random_configuration(4, rng)
    obj = ArticulatedObject(4)
    world = make_world(obj, conf, hands="baxter", preset="stiff", seed=6)
    k = rng.randint(1, 3)
    plane = rng.choice(["z-axis", "xy-axes"])
    sign = rng.choice([1, -1])
    world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sign, 10.0)
    world.run_until(world.time + 3.0)
    for hand in ("left", "right"):
        geoms = arm_geoms(world.model, hand, list(obj.links))
        dist, pair = clearance(world.model, world.data, geoms, world.hands.held(hand), False)
        assert dist >= 0.0, f"{hand}: {pair} {dist:.3f} m"
