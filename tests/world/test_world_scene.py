"""The MuJoCo object: MJCF from the model, configuration round trip, stability, hands, push."""

from __future__ import annotations

import random

import numpy as np
import pytest

from artiplan.model import ArticulatedObject, Configuration, direction_error, random_configuration
from artiplan.world.presets import preset
from artiplan.world.scene import World, WorldConfig


@pytest.mark.parametrize("n", [3, 6, 12])
def test_configuration_round_trips(n: int) -> None:
    obj = ArticulatedObject(n)
    for seed in range(3):
        conf = random_configuration(n, random.Random(seed))
        world = World(obj, conf)
        back = world.true_configuration()
        assert direction_error(conf, back).max() < 1e-4
        # The same cover as the one set (nearest the reference), not just the same directions.
        assert np.allclose(np.cos(np.radians(back.gamma)), np.cos(np.radians(conf.gamma)))
        world.set_configuration(random_configuration(n, random.Random(seed + 100)))
        assert direction_error(world.true_configuration(), conf).max() > 1.0


@pytest.mark.parametrize("preset_name", ["stiff", "loose"])
@pytest.mark.parametrize("n", [3, 8, 12])
def test_stable_for_a_few_seconds(n: int, preset_name: str) -> None:
    obj = ArticulatedObject(n)
    world = World(obj, random_configuration(n, random.Random(n)), WorldConfig(preset(preset_name)))
    world.step(3.0)
    assert np.all(np.isfinite(world.data.qpos))
    assert np.all(np.abs(world.data.qvel) < 100.0)  # rad/s: nothing exploded


def test_l1_stays_clamped_and_gravity_pulls_free_links_down() -> None:
    obj = ArticulatedObject(4)
    conf = Configuration.from_angles([30, 0, 0, 0], [90, 0, 0, 90])
    world = World(obj, conf, WorldConfig(preset("stiff")))
    world.step(2.0)
    now = world.true_configuration()
    assert direction_error(now, conf)[0] < 1e-6
    # Overdamped: L4 falls slowly toward 0, at the order of 0.1-1 deg/s.
    assert 90.0 - 2.0 * 2.0 < now.gamma[3] < 90.0 - 0.1 * 2.0


@pytest.mark.parametrize(
    ("k", "plane", "sign"), [(2, "z-axis", 1), (3, "xy-axes", -1), (1, "xy-axes", 1)]
)
@pytest.mark.parametrize("preset_name", ["stiff", "loose"])
def test_virtual_hands_rotate_30_degrees(k: int, plane: str, sign: int, preset_name: str) -> None:
    obj = ArticulatedObject(6)
    conf = random_configuration(6, random.Random(7))
    world = World(obj, conf, WorldConfig(preset(preset_name)))
    start = world.true_configuration()
    world.hold_and_rotate(f"L{k}", f"L{k + 1}", plane, sign, 10.0)
    world.run_until(3.0)
    world.stop(release=False)
    end = world.true_configuration()
    expected = start.with_angle(k + 1, plane, start.angle(k + 1, plane) + 30.0 * sign)
    assert direction_error(expected, end)[k] < 2.0  # reached within 2 deg
    assert direction_error(start, end)[k - 1] < 0.5  # the held link drifts < 0.5 deg
    # ... and it really moved (a theta turn moves a direction by less when gamma is near a pole).
    assert direction_error(start, end)[k] > 0.9 * direction_error(start, expected)[k] > 0.0


def test_push_turns_a_link_and_carries_the_rest() -> None:
    obj = ArticulatedObject(5)
    conf = Configuration.from_angles([0, 10, 20, 30, 40], [90, 100, 110, 120, 130])
    world = World(obj, conf)
    world.push("L3", "xy-axes", 25.0)
    now = world.true_configuration()
    assert now.theta[2] == pytest.approx(45.0, abs=1e-6)
    assert now.theta[1] == pytest.approx(10.0, abs=1e-6)
    # L4, L5 are carried rigidly: their directions turned by 25 deg about the vertical too.
    assert now.theta[3] == pytest.approx(55.0, abs=1e-6)
    with pytest.raises(ValueError, match="clamped"):
        world.push("L1", "z-axis", 5.0)


def test_motion_is_reported_and_stop_releases() -> None:
    world = World(ArticulatedObject(4), random_configuration(4, random.Random(2)))
    with pytest.raises(ValueError, match="neighbour"):
        world.hold_and_rotate("L1", "L3", "z-axis", 1)
    world.hold_and_rotate("L2", "L3", "z-axis", -1, 10.0)
    assert world.motion == ("L2", "L3", "z-axis", -1)
    assert {world.hands.held("left"), world.hands.held("right")} == {"L2", "L3"}
    world.step(0.1)
    world.stop()
    assert world.motion is None
    assert world.hands.held("left") is None and world.hands.held("right") is None


def test_a_long_turn_of_a_near_vertical_chain_stays_steady() -> None:
    """The rotating hand's servo must not oscillate: seeded 6-link task 11's first turn (hold
    L2, turn L3 about the vertical with L3-L4 near the upward pole) shook the held L2 by +-30
    deg within 3-5 s with the old integral gain (ki = 40); ki = 10 turns it smoothly."""
    from artiplan.encoding.suite import make_task
    from artiplan.world import VirtualHands

    obj = ArticulatedObject(6)
    w = World(obj, make_task(6, 11, seed=7).initial, WorldConfig(), VirtualHands())
    w.hold_and_rotate("L2", "L3", "xy-axes", -1, 10.0, extent_deg=80)
    held0 = w.true_configuration()
    fastest = 0.0
    for _ in range(140):  # 7 s
        w.run_until(w.time + 0.05)
        fastest = max(fastest, float(np.abs(w.data.qvel).max()))
    # A steady 10 deg/s turn is 0.17 rad/s; the oscillation reached 5-10 rad/s.
    assert fastest < 0.5
    assert direction_error(held0, w.true_configuration())[1] < 1.0  # the held L2 stays put
