"""Baxter's chosen grasps keep the arms clear of the torso, the other arm and the scene."""

from __future__ import annotations

import random

import mujoco
import numpy as np
import pytest

from artiplan.model import ArticulatedObject, Configuration, random_configuration
from artiplan.world import World, make_world
from artiplan.world.collision import ArmGeoms, _pairs, arm_contacts, arm_geoms, clearance


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


def _pairs_one_geom_at_a_time(
    model: mujoco.MjModel, data: mujoco.MjData, geoms: ArmGeoms, held: str | None,
    with_links: bool, margin: float, with_other: bool, with_body: bool,
) -> list[tuple[int, int]]:
    """The pre-filter as it was written first (a loop over the arm's geoms): the reference."""
    held_id = geoms.links.get(held, -1) if held is not None else -1
    pairs = []
    for a in geoms.arm:
        torso = () if a in geoms.shoulder or not with_body else geoms.torso
        obstacles = np.array([*torso, *(geoms.other if with_other else ()),
                              *(geoms.scene if with_body else ()),
                              *(geoms.links.values() if with_links else ())], dtype=int)
        if a in geoms.gripper:
            obstacles = obstacles[obstacles != held_id]
        gap = np.linalg.norm(data.geom_xpos[obstacles] - data.geom_xpos[a], axis=1)
        gap -= model.geom_rbound[obstacles] + model.geom_rbound[a]
        pairs += [(a, int(b)) for b in obstacles[gap < margin]]
    return pairs


def test_the_pair_prefilter_keeps_the_pairs_and_their_order() -> None:
    obj = ArticulatedObject(6)
    world = make_world(obj, random_configuration(6, random.Random(3)), hands="baxter")
    rng = np.random.default_rng(0)
    q = world.hands._q["left"]
    checked = 0
    # One ArmGeoms for every pose, as in a run: its cached arrays must not depend on the pose.
    geoms = arm_geoms(world.model, "left", list(obj.links))
    for _ in range(12):  # random left-arm poses, some into the torso, the links, the other arm
        world.data.qpos[q] = rng.uniform(-1.5, 1.5, size=len(q))
        mujoco.mj_kinematics(world.model, world.data)
        for held in (None, "L3"):
            for flags in ((True, True, True), (False, True, True), (True, False, False)):
                for margin in (0.01, 0.05, 0.2):
                    args = (world.model, world.data, geoms, held, flags[0], margin, *flags[1:])
                    got = _pairs(*args)
                    assert got == _pairs_one_geom_at_a_time(*args)
                    checked += len(got)
    assert checked > 0
    # The held link is never paired with the gripper; the shoulder never with the torso.
    pairs = _pairs(world.model, world.data, geoms, "L3", True, 10.0)
    assert (geoms.gripper[0], geoms.links["L3"]) not in pairs
    assert (geoms.arm[0], geoms.links["L3"]) in pairs
    assert not {(a, t) for a in geoms.shoulder for t in geoms.torso} & set(pairs)


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


def _blind_turn(impact_stop_m: float | None, strain_stop: bool = False
                ) -> tuple[World, float, float]:
    """4 links, seed 10, grasps chosen blind (``avoid_collisions=False``): hold L3, rotate L4
    by -90 deg on xy-axes for 9 s with the world's ``impact_stop_m`` and ``strain_stop``.
    The world, the turn's start [s] and the deepest arm contact that began over 1 s into it [m]."""
    rng = random.Random(10)
    conf = random_configuration(4, rng)
    world = make_world(ArticulatedObject(4), conf, hands="baxter", preset="stiff", seed=10,
                       avoid_collisions=False, impact_stop_m=impact_stop_m,
                       strain_stop=strain_stop)
    k = rng.randint(1, 3)
    plane = rng.choice(["z-axis", "xy-axes"])
    sign = rng.choice([1, -1])
    world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sign, 10.0, extent_deg=90)
    t0 = world.time
    world.run_until(t0 + 9.0)
    late = [e.depth_m for e in world.hands.contacts.events if e.start > t0 + 1.0]
    return world, t0, max(late, default=0.0)


@pytest.mark.slow
@pytest.mark.ci
def test_baxter_turn_stops_on_impact_when_asked() -> None:
    """:func:`_blind_turn` drives the right wrist into the torso at ~6.25 s into the turn.
    With ``impact_stop_m`` the turn's command stops at the first contact deeper than that;
    the arm's lag still carries it ~19 mm into the head (as deep as without the stop), but
    nothing touches from 0.5 s after the stop on, where the unstopped turn goes on into more
    contacts (the left wrist 9.5 mm into L4 at ~8.2 s). (With the stiff preset's old
    armature, 1e-4, the unstopped wrist went 54 mm into the torso.)"""
    runs = {}
    for imp in (None, 0.005):
        world, _, deepest = _blind_turn(impact_stop_m=imp)
        runs[imp] = (world, deepest)
        if imp is None:
            assert not world.impacts
            continue
        assert len(world.impacts) == 1
        when, geoms, depth = world.impacts[0]
        assert depth > imp and any("right" in g for g in geoms)
        assert world.turn_ends is not None and abs(world.turn_ends - when) < 1e-6
        assert world.turn_limit is not None and "impact" in world.turn_limit[1]
    stopped = runs[0.005][0].impacts[0][0]

    def after(world: World) -> float:
        return max((e.depth_m for e in world.hands.contacts.events if e.start > stopped + 0.5),
                   default=0.0)

    assert runs[None][1] > 0.015
    assert after(runs[None][0]) > 0.005
    assert after(runs[0.005][0]) < 0.001


def test_baxter_turn_stops_on_strain_when_asked() -> None:
    """:func:`_blind_turn` with the impact stop off: the torso holds the right wrist, its
    servo winds up to its bound, and ``strain_stop`` stops the turn's command there (the arm
    then goes less deep than without); without it the turn goes on."""
    deepest = {}
    for strain in (False, True):
        world, t0, deepest[strain] = _blind_turn(impact_stop_m=None, strain_stop=strain)
        if not strain:
            assert not world.impacts
            continue
        assert len(world.impacts) == 1
        when, (hand, what), _ = world.impacts[0]
        assert hand == "right" and what == "servo bound" and when < t0 + 9.0
        assert world.turn_limit is not None and "strain" in world.turn_limit[1]
    assert deepest[True] < deepest[False]
