"""Baxter: both arms reach, one holds a link, the other rotates its neighbour (slow: ~2-4 s)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from artiplan.model import ArticulatedObject, Configuration, direction_error
from artiplan.world import make_world
from artiplan.world.rotations import quat_to_mat


@pytest.mark.slow
@pytest.mark.ci
@pytest.mark.parametrize(("k", "plane", "sign"), [(2, "z-axis", 1), (2, "xy-axes", -1)])
def test_baxter_holds_within_half_a_degree_while_rotating_30(k: int, plane: str, sign: int) -> None:
    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter", preset="stiff")
    start = world.true_configuration()
    world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sign, 10.0)
    assert {world.hands.held("left"), world.hands.held("right")} == {f"L{k}", f"L{k + 1}"}
    world.run_until(3.0)
    world.stop(release=False)
    end = world.true_configuration()
    expected = start.with_angle(k + 1, plane, start.angle(k + 1, plane) + 30.0 * sign)
    assert direction_error(expected, end)[k] < 2.0
    assert direction_error(start, end)[k - 1] < 0.5
    assert direction_error(start, end)[k] > 10.0
    # The motors stay within Baxter's limits (they are clipped; check they are not saturated).
    for hand in ("left", "right"):
        limits = world.hands.model.actuator_ctrlrange[world.hands._act[hand], 1]
        assert (abs(world.hands.last_torque[hand]) < limits).all()


@pytest.mark.slow
def test_baxter_approaches_in_simulated_time_then_rotates() -> None:
    from artiplan.world.baxter import BaxterHands, baxter_layout
    from artiplan.world.presets import preset
    from artiplan.world.scene import World, WorldConfig

    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    layout = baxter_layout(obj)
    world = World(
        obj, conf, WorldConfig(preset("stiff"), layout=layout), BaxterHands(approach_s=1.0)
    )
    world.hold_and_rotate("L2", "L3", "z-axis", 1, 10.0)
    # The planned, limit-timed motions take simulated time: at least approach_s, then 0.2 s
    # of settling; and end at the grasp (only a small correction for what the links moved).
    assert 1.2 <= world.time < 6.0
    assert world.hands.checker.stats and world.hands.checker.stats[-1].ok
    assert max(world.hands.last_jump_m.values()) < 0.02
    start = world.true_configuration()
    world.run_until(world.time + 3.0)
    world.stop(release=False)
    end = world.true_configuration()
    expected = start.with_angle(3, "z-axis", start.gamma[2] + 30.0)
    assert direction_error(expected, end)[2] < 2.0
    assert direction_error(start, end)[1] < 0.5


def _fractions(world, hand: str, link: str, first: int | None = None) -> set[float]:
    """Where along ``link`` [fraction of its length from its base joint] the grasp points are
    (of the ``first`` grasp poses)."""
    hands = world.hands
    b = world.model.body(link).id
    base, u = world.data.xpos[b], -world.data.xmat[b].reshape(3, 3)[:, 2]
    out = set()
    for pos, quat in hands.grasp_poses(hand, link, tiers=5)[:first]:
        point = pos + hands._depth * quat_to_mat(quat)[:, 2]  # between the finger pads
        out.add(round(float(np.dot(point - base, u)) / world.obj.link_length, 3))
    return out


def test_baxter_grasp_candidates_include_points_away_from_the_shared_joint() -> None:
    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter")
    hands = world.hands
    hands.assign("L2", "L3")  # L2 and L3 share J3: L2's tip, L3's base
    first = hands.tier_size("L2")
    # Tier 1: the centre and a quarter length away from the shared joint; tier 2 (tried when
    # tier 1 has no collision-free pair) adds a point on the other side and tilted approaches.
    assert _fractions(world, "left", "L2", first) == {0.5, 0.25}
    assert _fractions(world, "right", "L3", hands.tier_size("L3")) == {0.5, 0.75}
    assert _fractions(world, "left", "L2", hands.tier_end("L2", 2)) == {0.5, 0.25, 0.75}
    assert _fractions(world, "right", "L3", hands.tier_end("L3", 2)) == {0.5, 0.75, 0.35}


def test_baxter_tier_three_turns_the_approaches_of_tiers_one_and_two_half_a_step() -> None:
    """Tier 3's poses are tiers 1-2's, in order, at the same grasp points with the same tilt
    along the link, each approach turned half a step (22.5 deg of the 8-step turn) further
    about the link: 16 approach directions where tiers 1-2 have 8."""
    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter")
    hands = world.hands
    hands.assign("L2", "L3")
    for hand, link in (("left", "L2"), ("right", "L3")):
        b = world.model.body(link).id
        u = -world.data.xmat[b].reshape(3, 3)[:, 2]
        poses = hands.grasp_poses(hand, link, tiers=3)
        old, new = poses[: hands.tier_end(link, 2)], poses[hands.tier_end(link, 2):]
        assert len(new) == len(old) == len(poses) // 2
        for (p1, q1), (p2, q2) in zip(old, new, strict=True):
            z1, z2 = quat_to_mat(q1)[:, 2], quat_to_mat(q2)[:, 2]
            # The grasp point between the pads, and the tilt along the link, are kept.
            np.testing.assert_allclose(p1 + hands._depth * z1, p2 + hands._depth * z2,
                                       atol=1e-9)
            assert np.dot(z1, u) == pytest.approx(np.dot(z2, u), abs=1e-9)
            # The approach's part across the link turned 22.5 deg about it, the same way.
            a1, a2 = z1 - np.dot(z1, u) * u, z2 - np.dot(z2, u) * u
            turn = np.degrees(np.arctan2(np.dot(np.cross(a1, a2), u), np.dot(a1, a2)))
            assert turn == pytest.approx(22.5, abs=1e-6)


def test_baxter_tier_four_grasps_near_the_ends_and_tier_five_shallower() -> None:
    """Tier 4 grasps near the links' ends (both ends of the held link, the far end of the
    rotated one); tier 5's poses are tier 1's (same points, approaches and finger ways) with
    the link SHALLOW_M nearer the fingertips: the hand SHALLOW_M further back."""
    from artiplan.world.grasping import END_NEAR, SHALLOW_M

    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter")
    hands = world.hands
    hands.assign("L2", "L3")
    ends = {"L2": {END_NEAR, 1 - END_NEAR}, "L3": {1 - END_NEAR}}
    for hand, link in (("left", "L2"), ("right", "L3")):
        poses = hands.grasp_poses(hand, link, tiers=5)
        first = hands.tier_size(link)
        assert hands.tier_end(link, 5) == len(poses)
        assert hands.tier_end(link, 2) == len(hands.grasp_poses(hand, link, tiers=2))
        tier4 = (hands.tier_end(link, 3), hands.tier_end(link, 4))
        assert _fractions(world, hand, link, tier4[1]) - _fractions(
            world, hand, link, tier4[0]) == ends[link]
        deep, shallow = poses[:first], poses[tier4[1]:]
        for (p1, q1), (p2, q2) in zip(deep, shallow, strict=True):
            np.testing.assert_allclose(q1, q2)
            np.testing.assert_allclose(p2 - p1, -SHALLOW_M * quat_to_mat(q1)[:, 2], atol=1e-12)


def test_baxter_assign_picks_the_pairing_in_which_both_hands_reach(monkeypatch) -> None:
    """The right hand is made unable to reach L3 (every candidate 2 cm short): the pairing
    left-holds/right-rotates is then refused although its scores are otherwise as good."""
    from artiplan.world.grasping import UNREACHABLE

    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter")
    hands = world.hands
    real = hands.candidates

    def right_misses_l3(hand: str, link: str, tier: int = 1) -> list:
        out = real(hand, link, tier)
        if (hand, link) != ("right", "L3"):
            return out
        return [replace(c, miss=0.02, score=c.score + UNREACHABLE, sweep=[]) for c in out]

    monkeypatch.setattr(hands, "candidates", right_misses_l3)
    assert any(c.reachable for c in hands.candidates("left", "L3"))  # the other pairing reaches
    assert any(c.reachable for c in hands.candidates("right", "L2"))
    assert hands.assign("L2", "L3") == ("right", "left")
    world.hold_and_rotate("L2", "L3", "z-axis", 1, 10.0)  # grasps without OutOfReachError
    assert hands.held("right") == "L2" and hands.held("left") == "L3"


def test_baxter_grasp_raises_only_when_no_candidate_reaches(monkeypatch) -> None:
    from artiplan.world.baxter import OutOfReachError

    obj = ArticulatedObject(4)
    world = make_world(obj, hands="baxter")
    hands = world.hands
    real = hands.candidates
    monkeypatch.setattr(
        hands,
        "candidates",
        lambda h, link, tier=1: [replace(c, miss=0.03, score=c.score + 10.0)
                                 for c in real(h, link, tier)],
    )
    with pytest.raises(OutOfReachError, match="cannot reach L3"):
        hands.grasp("right", "L3")
    monkeypatch.undo()
    hands.grasp("right", "L3")  # the real candidates reach
    assert hands.held("right") == "L3"


def _released_after_a_turn():  # type: ignore[no-untyped-def]
    """A 4-link Baxter world (1 s approach) whose hands just let go after turning L3: both
    hands start on the object."""
    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(obj, conf, hands="baxter", approach_s=1.0)
    world.hold_and_rotate("L2", "L3", "z-axis", 1, 10.0)
    world.run_until(world.time + 0.5)
    world.stop(release=True)
    return world


@pytest.mark.slow
def test_baxter_approach_backs_off_from_the_object_first() -> None:
    world = _released_after_a_turn()
    hands = world.hands
    axes = {h: world.data.xmat[hands._hand[h]].reshape(3, 3)[:, 2].copy() for h in hands.names}
    starts = {h: world.data.xpos[hands._hand[h]].copy() for h in hands.names}
    backed: dict[str, float] = {h: 0.0 for h in hands.names}
    runs: list[tuple[tuple[str, ...], float]] = []
    real_run = hands._run

    def run(moving, path, advance, settle_s=0.2):  # type: ignore[no-untyped-def]
        runs.append((moving, path.duration))
        real_run(moving, path, advance, settle_s)
        if len(runs) == 1:  # the back-off: how far back along the approach axis
            for h in moving:
                moved = world.data.xpos[hands._hand[h]] - starts[h]
                backed[h] = -float(np.dot(moved, axes[h]))

    hands._run = run
    t0 = world.time
    hold, rot = hands.assign("L3", "L4")
    hands.approach([(hold, "L3"), (rot, "L4")], world.step)
    # Both hands were on the object: the first motion backs both off along their axes
    # (6 cm commanded; the servo lags a little), then transfer and final leg.
    assert runs[0][0] == ("left", "right") and len(runs) == 3
    assert min(backed.values()) > 0.04, backed
    assert world.time - t0 == pytest.approx(sum(d for _, d in runs) + 0.2, abs=0.01)
    world.hands.grasp(hold, "L3")
    world.hands.grasp(rot, "L4")
    assert max(hands.last_jump_m.values()) < 0.03


@pytest.mark.slow
def test_baxter_approach_goes_through_the_pre_grasp_pose_and_stays_clear() -> None:
    from artiplan.world.approach import PREGRASP_M
    from artiplan.world.collision import arm_geoms, clearance
    from artiplan.world.rotations import quat_to_mat

    world = _released_after_a_turn()
    hands = world.hands
    hold, rot = hands.assign("L3", "L4")
    links = {hold: "L3", rot: "L4"}
    grasps = {h: hands._chosen(h, links[h]) for h in links}
    geoms = {h: arm_geoms(world.model, h, list(world.obj.links)) for h in links}
    at_pre: dict[str, np.ndarray] = {}
    worst = {h: np.inf for h in links}  # smallest clearance during the approach
    real_run = hands._run
    runs: list[int] = []

    def run(moving, path, advance, settle_s=0.2):  # type: ignore[no-untyped-def]
        real_run(moving, path, advance, settle_s)
        runs.append(1)
        if len(runs) == 2:  # after the back-off and the transfer: at the pre-grasp poses
            at_pre.update({h: world.data.xpos[hands._hand[h]].copy() for h in links})

    def advance(dt: float) -> None:
        world.step(dt)
        for h in links:  # fingers included; only the hand's own link may be touched
            dist = clearance(world.model, world.data, geoms[h], links[h])[0]
            worst[h] = min(worst[h], dist)

    hands._run = run
    hands.approach([(hold, "L3"), (rot, "L4")], advance)
    for h, c in grasps.items():
        # The pre-grasp pose is the grasp moved PREGRASP_M back along the hand's z axis ...
        pre_pos, pre_quat = hands._hand_pose(h, hands.last_pregrasp[h])
        expected = c.pos - PREGRASP_M * quat_to_mat(c.quat)[:, 2]
        assert np.linalg.norm(pre_pos - expected) < 0.003
        assert abs(abs(float(np.dot(pre_quat, c.quat))) - 1.0) < 1e-4
        # ... where the arm is when the transfer ends (servo lag), before closing in.
        assert np.linalg.norm(at_pre[h] - expected) < 0.02, h
    # Before the pre-grasp approach (one joint-space leg), the holding hand's fingers went
    # 2 mm into a neighbouring link as they closed in (4-5 cm from the grasp); now the motions
    # are planned and the physics has arm contacts on: nothing is touched.
    assert worst[hold] > 0.0 and worst[rot] > 0.0, worst
    assert not hands.contacts.events, [e.to_dict() for e in hands.contacts.events]


def test_baxter_says_which_link_no_hand_can_grasp() -> None:
    """A 6-link chain folded so that L4 lies between L2 and L5 (perceived in a seeded 6-link
    run, task 2 at 30.2 s): every grasp of L4 by either hand meets another link or the scene
    at the grasp or on its final leg. The refusal names L4 in its role and what its grasps
    met, so the loop plans no other turn of L4 before L4 has moved against them."""
    from artiplan.world.pairs import NotExecutableError

    conf = Configuration((268.59, 207.12, 351.83, 71.93, 219.86, 221.24),
                         (16.17, 33.53, 135.14, 140.66, 57.26, 56.96))
    world = make_world(ArticulatedObject(6), conf, hands="baxter", approach_s=1.0)
    with pytest.raises(NotExecutableError) as err:
        world.hold_and_rotate("L3", "L4", "xy-axes", 1, 10.0, extent_deg=40.0)
    blocked = {(link, role): met for link, role, met in err.value.blocked}
    assert ("L4", "turn") in blocked
    assert 5 in blocked[("L4", "turn")]  # L5, folded back beside it, among what was met
    assert ("L3", "hold") not in blocked  # L3 itself can be held
    assert world.hands.held("left") is None and world.hands.held("right") is None


def test_baxter_refuses_a_grasp_whose_last_jump_would_go_into_the_other_arm(monkeypatch) -> None:
    """A grasp's IK is solved again where the link is when the arm arrives and the arm
    jumps there: a solution 3 cm into the other arm is refused (measured: such a jump made
    MuJoCo's step diverge), and the arm stays where it was."""
    from artiplan.world.pairs import NotExecutableError

    conf = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])
    world = make_world(ArticulatedObject(4), conf, hands="baxter")
    hands = world.hands
    into_left = np.array([1.311, 0.18, 1.961, 0.9, -1.287, 0.598, 0.723])  # 3.4 cm into it
    monkeypatch.setattr(hands, "_grasp_solution", lambda hand, link: (into_left, 0.0))
    before = world.data.qpos.copy()
    with pytest.raises(NotExecutableError, match="right hand's grasp of L3 would put it"):
        hands.grasp("right", "L3")
    assert np.array_equal(world.data.qpos, before) and hands.held("right") is None


@pytest.mark.slow
@pytest.mark.ci  # ~3 s
def test_baxter_a_joint_between_two_grasped_links_stays_calm() -> None:
    """The object's joints chattered between two welded grippers (armature 1e-4: peak 1083
    rad/s^2 here; MuJoCo diverged in 6-link task 11 when the grippers then touched); the
    stiff preset's armature keeps them calm (58 rad/s^2 measured)."""
    from artiplan.encoding.suite import make_task

    obj = ArticulatedObject(6)
    world = make_world(obj, make_task(6, 11, seed=7).initial, hands="baxter", preset="stiff")
    m = world.model
    dofs = [i for i in range(m.nv) if m.joint(int(m.dof_jntid[i])).name.startswith("J")]
    assert len(dofs) == 3 * (obj.n_links - 1)
    world.hold_and_rotate("L2", "L3", "xy-axes", 1, extent_deg=20.0)
    peak = 0.0
    for _ in range(250):  # 0.5 s
        world.step()
        peak = max(peak, float(np.abs(world.data.qacc[dofs]).max()))
    assert peak < 300.0
