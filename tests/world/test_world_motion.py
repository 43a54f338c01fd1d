"""Baxter's arms: contacts on in the physics, timed trajectories, planned (OMPL) motions, and
grasp pairs refused when nothing is collision-free."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

from artiplan.model import ArticulatedObject, Configuration
from artiplan.world import make_world
from artiplan.world.motion import MARGIN_M, NEAR_CLEARANCE_M, TRANSFER_CLEARANCE_M, Query, plan_path
from artiplan.world.timing import ACCELERATION, VELOCITY, Limits, TimedPath

CONF = Configuration.from_angles([180, 90, 60, 30], [90, 100, 80, 60])


def _collide(model: mujoco.MjModel, a: str, b: str) -> bool:
    """Whether MuJoCo's contact filter lets geoms ``a`` and ``b`` collide."""
    ga, gb = model.geom(a).id, model.geom(b).id
    return bool(model.geom_contype[ga] & model.geom_conaffinity[gb]) or bool(
        model.geom_contype[gb] & model.geom_conaffinity[ga])


def test_timed_path_keeps_baxters_limits_and_its_straight_segments() -> None:
    rng = np.random.default_rng(3)
    wps = [rng.uniform(-1.0, 1.0, 14) for _ in range(3)]
    path = TimedPath(wps, Limits())
    ts = np.arange(0.0, path.duration + 1e-9, 0.002)
    qs = np.array([path.at(t)[0] for t in ts])
    vs = np.array([path.at(t)[1] for t in ts])
    vmax = np.array(VELOCITY * 2)
    assert (np.abs(vs) <= vmax * 1.001).all()
    acc = np.diff(vs, axis=0) / 0.002
    assert (np.abs(acc) <= np.array(ACCELERATION * 2) * 1.05).all()
    assert np.allclose(path.at(0.0)[0], wps[0]) and np.allclose(path.at(path.duration)[0], wps[2])
    # Rest-to-rest per segment, all joints in proportion: every sample lies on a segment.
    for q in qs[::25]:
        off = min(np.linalg.norm((q - a) - np.dot(q - a, b - a) / np.dot(b - a, b - a) * (b - a))
                  for a, b in zip(wps, wps[1:], strict=False))
        assert off < 1e-6
    slow = TimedPath(wps, Limits(), min_duration=2 * path.duration)
    assert slow.duration == pytest.approx(2 * path.duration)
    assert np.allclose(slow.at(slow.duration / 2)[0], path.at(path.duration / 2)[0])


def test_contact_bits_make_arms_collide_with_the_scene_the_object_and_each_other() -> None:
    world = make_world(ArticulatedObject(4), CONF, hands="baxter")
    m = world.model
    pre = "baxter_"
    assert _collide(m, f"{pre}left_w2_collision", "L3_geom")
    assert _collide(m, f"{pre}left_w2_collision", f"{pre}right_w2_collision")
    assert _collide(m, f"{pre}left_upper_forearm_col", f"{pre}base_link_col")  # torso
    for scene in ("table", "fixture_block", "fixture_arm", "baxter_pedestal", "floor"):
        assert _collide(m, f"{pre}right_gripper_gripper_base_col", scene), scene
    assert _collide(m, f"{pre}right_gripper_l_finger_g0", "L2_geom")
    # Not: an arm with itself, the shoulder housings with the torso hull they sit in, links
    # with each other, links with the fixture that clamps L1.
    assert not _collide(m, f"{pre}left_w2_collision", f"{pre}left_upper_elbow_col")
    assert not _collide(m, f"{pre}left_s0_collision", f"{pre}base_link_col")
    assert not _collide(m, "L1_geom", "L2_geom")
    assert not _collide(m, "L1_geom", "fixture_block")


def test_a_held_link_is_free_of_its_gripper_and_the_others_are_not() -> None:
    world = make_world(ArticulatedObject(4), CONF, hands="baxter")
    hands = world.hands
    world.hold_and_rotate("L2", "L3", "z-axis", 1, 10.0)
    m = world.model
    for hand in hands.names:
        link = hands.held(hand)
        assert link is not None
        finger = f"baxter_{hand}_gripper_l_finger_g0"
        assert not _collide(m, finger, f"{link}_geom")
        assert _collide(m, finger, "L4_geom")
    world.stop(release=True)
    # Let go of, the links touch the grippers again once the grippers have left them.
    world.hands.retreat(["left", "right"], world.step)
    for hand in hands.names:
        assert _collide(m, f"baxter_{hand}_gripper_l_finger_g0", "L2_geom")
        assert _collide(m, f"baxter_{hand}_gripper_l_finger_g0", "L3_geom")


def test_an_arm_driven_blindly_to_a_grasp_is_stopped_and_the_collision_logged() -> None:
    """Sent straight (no planned motion) from home to a grasp of L3, the right hand's finger
    meets the fixture block: the physics stops it short of the grasp, and the log says which
    geoms, when and how deep."""
    world = make_world(ArticulatedObject(4), CONF, hands="baxter", approach_s=1.0)
    hands = world.hands
    c = hands.best_grasp("right", "L3")
    hands._target_q["right"] = c.q.copy()  # no approach, no close-in, no weld
    world.run_until(1.5)
    events = [e for e in hands.contacts.events if "fixture_block" in e.geoms]
    assert events, [e.to_dict() for e in hands.contacts.events]
    first = events[0]
    assert first.depth_m > 0.0005 and 0.0 < first.start < 1.5
    assert any("right_gripper" in g for g in first.geoms)
    short = np.linalg.norm(world.data.xpos[hands._hand["right"]] - c.pos)
    assert short > 0.01  # blocked: contacts are on (the joints alone would get there)


@pytest.mark.slow
def test_transfer_is_planned_around_what_the_straight_motion_hits() -> None:
    """4 links, home pose to the pre-grasp poses of hold L2 / rotate L3: the straight
    joint-space motion puts a finger through the fixture block; the planned one keeps clear
    at every 0.01 rad and the simulated arms stay clear every 20 ms."""
    world = make_world(ArticulatedObject(4), CONF, hands="baxter", approach_s=1.0)
    hands = world.hands
    hold, rot = hands.assign("L2", "L3")
    legs = {h: hands._leg(hands._plan[h][0]) for h in (hold, rot)}
    moving = tuple(h for h in hands.names if h in legs)
    start = np.concatenate([world.data.qpos[hands._q[h]] for h in moving])
    goal = np.concatenate([legs[h][0] for h in moving])
    chk = hands.checker
    chk.sync(world.data.qpos)
    query = Query(moving)
    assert not chk.segment_valid(start, goal, query)
    path = plan_path(chk, query, start, goal, hands._bounds(moving))
    assert path is not None and len(path) > 2
    assert chk.path_valid(path, query)
    worst = np.inf

    def advance(dt: float) -> None:
        nonlocal worst
        world.step(dt)
        chk.sync(world.data.qpos)
        q = {h: world.data.qpos[hands._q[h]] for h in moving}
        worst = min(worst, chk.clearance(q, Query(moving, hands.grip_pairs(
            {hold: "L2", rot: "L3"})))[0])

    hands.approach([(hold, "L2"), (rot, "L3")], advance)
    assert worst > 0.0
    assert not hands.contacts.events
    assert hands.checker.stats and all(s.ok for s in hands.checker.stats)


@pytest.mark.slow
def test_both_arms_move_one_by_one_when_the_14d_query_finds_nothing(monkeypatch) -> None:
    """The 14-D transfer made to find nothing: each arm is planned alone (7-D, the other arm
    where it stands), one after the other; every segment moves one arm, and the simulated
    arms keep clear on the way."""
    import artiplan.world.approach as approach

    real = approach.plan_path

    def no_14d(chk, query, start, goal, bounds, time_s=2.0):  # type: ignore[no-untyped-def]
        return None if len(start) == 14 else real(chk, query, start, goal, bounds, time_s)

    monkeypatch.setattr(approach, "plan_path", no_14d)
    world = make_world(ArticulatedObject(4), CONF, hands="baxter", approach_s=1.0)
    hands = world.hands
    paths: list[list[np.ndarray]] = []
    one_by_one = hands._one_by_one

    def recorded(*args, **kwargs):  # type: ignore[no-untyped-def]
        out = one_by_one(*args, **kwargs)
        paths.append(out)
        return out

    monkeypatch.setattr(hands, "_one_by_one", recorded)
    hold, rot = hands.assign("L2", "L3")
    chk = hands.checker
    worst = np.inf

    def advance(dt: float) -> None:
        nonlocal worst
        world.step(dt)
        chk.sync(world.data.qpos)
        q = {h: world.data.qpos[hands._q[h]] for h in hands.names}
        worst = min(worst, chk.clearance(q, Query(hands.names, hands.grip_pairs(
            {hold: "L2", rot: "L3"})))[0])

    hands.approach([(hold, "L2"), (rot, "L3")], advance)
    assert paths and paths[0] is not None and len(paths[0]) >= 3
    for a, b in zip(paths[0], paths[0][1:], strict=False):
        moved = [not np.allclose(a[7 * i : 7 * i + 7], b[7 * i : 7 * i + 7]) for i in (0, 1)]
        assert moved.count(True) == 1
    assert worst > 0.0 and not hands.contacts.events


def test_no_collision_free_pair_makes_the_action_not_executable(monkeypatch) -> None:
    """If every configuration collided (the checker made to say so), no pair is chosen: the
    action is refused with the reason, and nothing is held."""
    from artiplan.world.motion import ArmChecker
    from artiplan.world.pairs import NotExecutableError

    world = make_world(ArticulatedObject(4), CONF, hands="baxter")
    monkeypatch.setattr(ArmChecker, "valid", lambda self, q, query, flat=None: False)
    with pytest.raises(NotExecutableError, match="no collision-free grasps to hold L2 and rotate"):
        world.hold_and_rotate("L2", "L3", "z-axis", 1, 10.0)
    assert world.hands.held("left") is None and world.hands.held("right") is None


def test_clearance_beyond_the_contact_margin_is_refused() -> None:
    world = make_world(ArticulatedObject(4), CONF, hands="baxter")
    chk = world.hands.checker
    q = {h: world.data.qpos[world.hands._q[h]] for h in world.hands.names}
    assert chk.valid(q, Query(world.hands.names, clearance=NEAR_CLEARANCE_M))
    with pytest.raises(ValueError, match="contact margin"):
        chk.valid(q, Query(world.hands.names, clearance=MARGIN_M + 0.01))


def test_baxter_beyond_six_links_is_a_usage_error(tmp_path) -> None:  # type: ignore[no-untyped-def]
    import subprocess
    import sys

    from artiplan.errors import UsageError

    with pytest.raises(UsageError, match="up to 6 links"):
        make_world(ArticulatedObject(8), hands="baxter")
    proc = subprocess.run(
        [sys.executable, "-m", "artiplan", "demo", "--links", "8", "--hands", "baxter",
         "--no-animation", "-o", str(tmp_path / "out")],
        capture_output=True, text=True, check=False, timeout=120,
    )
    assert proc.returncode == 2, proc.stderr
    assert "up to 6 links" in proc.stderr + proc.stdout


def _reference_contacts(chk, query):  # type: ignore[no-untyped-def]
    """What ArmChecker.contacts means, written plainly (the data after set_arms)."""
    m, d = chk.model, chk.data
    mujoco.mj_kinematics(m, d)
    mujoco.mj_collision(m, d)
    ks = [chk._names.index(h) for h in query.hands]
    out = []
    for i in range(d.ncon):
        a, b = int(d.contact.geom[i][0]), int(d.contact.geom[i][1])
        o1, o2 = int(chk._owner[a]), int(chk._owner[b])
        if o1 not in ks and o2 not in ks:
            continue
        if query.pairs == "solo" and o1 >= 0 and o2 >= 0:
            continue
        if query.pairs == "arms" and (o1 < 0 or o2 < 0):
            continue
        if (min(a, b), max(a, b)) in query.allowed:
            continue
        dist = float(d.contact.dist[i])
        out.append((a, b, dist) if o1 >= 0 else (b, a, dist))
    return out


def test_the_fast_validity_check_agrees_with_its_plain_definition() -> None:
    from artiplan.world.motion import ramped

    world = make_world(ArticulatedObject(4), CONF, hands="baxter")
    chk = world.hands.checker  # type: ignore[attr-defined]
    chk.sync(world.data.qpos.copy())
    home = np.concatenate([world.data.qpos[chk.qadr[h]] for h in ("left", "right")])
    rng = np.random.default_rng(11)
    flats = [home + rng.normal(0.0, 0.5, 14) for _ in range(300)]
    grip = chk.gripper["right"]
    allowed = frozenset((min(int(g), chk.links["L3"]), max(int(g), chk.links["L3"])) for g in grip)
    queries = [Query(("left", "right")), Query(("right",), allowed, NEAR_CLEARANCE_M, "solo"),
               Query(("left", "right"), pairs="arms"),
               Query(("left", "right"), clearance=ramped([(flats[0], 0.004), (flats[1], 0.03)]))]
    seen = 0
    for flat in flats:
        for query in queries:
            q = chk.split(query.hands, flat[: 7 * len(query.hands)])
            chk.set_arms(q)
            ref = _reference_contacts(chk, query)
            chk.set_arms(q)
            assert chk.contacts(query) == ref
            need = query.clearance(flat[: 7 * len(query.hands)]) if callable(query.clearance) \
                else query.clearance
            assert chk.valid(q, query, flat[: 7 * len(query.hands)]) == all(
                dist >= need for _, _, dist in ref)
            seen += bool(ref)
    assert seen > 100  # most checks had contacts to filter, not only empty ones


def test_path_clearance_agrees_with_path_valid_at_every_clearance() -> None:
    """One pass of path_clearance answers what path_valid answers per clearance: the home pose
    to the pre-grasp poses of hold L2 / rotate L3 in a straight line (a finger goes through
    the fixture) and each arm's final leg."""
    world = make_world(ArticulatedObject(4), CONF, hands="baxter", approach_s=1.0)
    hands = world.hands
    hold, rot = hands.assign("L2", "L3")
    chk = hands.checker
    chk.sync(world.data.qpos)
    legs = {h: hands._leg(hands._plan[h][0]) for h in (hold, rot)}
    moving = tuple(h for h in hands.names if h in legs)
    start = np.concatenate([world.data.qpos[hands._q[h]] for h in moving])
    goal = np.concatenate([legs[h][0] for h in moving])
    cases = [([start, goal], Query(moving))]
    cases += [(legs[h], Query((h,), hands.grip_pairs({h: link}))) for h, link in
              ((hold, "L2"), (rot, "L3"))]
    seen = []
    for path, query in cases:
        clear = chk.path_clearance(path, query)
        seen.append(clear)
        for need in (-0.01, 0.0, NEAR_CLEARANCE_M, 0.01, MARGIN_M):
            q = Query(query.hands, query.allowed, need)
            assert (clear >= need) == chk.path_valid(path, q)
            stopped = chk.path_clearance(path, query, stop_below=need)
            assert (stopped >= need) == (clear >= need)
    # the straight motion is refused at the transfer clearance, the legs are clear
    assert seen[0] < TRANSFER_CLEARANCE_M and min(seen[1:]) >= NEAR_CLEARANCE_M
