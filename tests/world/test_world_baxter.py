"""Baxter: both arms reach, one holds a link, the other rotates its neighbour (slow: ~2-4 s)."""

from __future__ import annotations

import pytest

from artiplan.model import ArticulatedObject, Configuration, direction_error
from artiplan.world import make_world


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
    assert world.time == pytest.approx(1.2, abs=0.01)  # approach + settling: simulated time
    assert max(world.hands.last_jump_m.values()) < 0.02  # only a small final correction
    start = world.true_configuration()
    world.run_until(world.time + 3.0)
    world.stop(release=False)
    end = world.true_configuration()
    expected = start.with_angle(3, "z-axis", start.gamma[2] + 30.0)
    assert direction_error(expected, end)[2] < 2.0
    assert direction_error(start, end)[1] < 0.5
