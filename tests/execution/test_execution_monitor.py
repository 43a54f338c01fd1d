"""The monitor fires on an injected error and not on perception noise below its threshold."""

from __future__ import annotations

import random

import numpy as np
import pytest

from artiplan.execution import Monitor
from artiplan.execution.calibrate import fit_fall
from artiplan.execution.problem import canonical
from artiplan.model import ArticulatedObject, direction_error, random_configuration


def test_fires_on_injected_error_and_names_the_link() -> None:
    obj = ArticulatedObject(4)
    pred = random_configuration(4, random.Random(3)).with_angle(3, "z-axis", 90.0)
    off = pred.with_angle(3, "z-axis", 90.0 + 12.0)  # a 12 deg direction error on L3
    verdict = Monitor(obj, 8.0).check(pred, off)
    assert verdict.fired
    assert verdict.worst_link == "L3"
    assert verdict.worst_error == pytest.approx(12.0, abs=1e-6)
    assert not Monitor(obj, 15.0).check(pred, off).fired


def test_does_not_fire_on_perception_noise_below_threshold() -> None:
    from artiplan.world import make_world

    obj = ArticulatedObject(4)
    conf = random_configuration(4, random.Random(5))
    world = make_world(obj, conf, seed=11)
    truth = world.true_configuration()
    monitor = Monitor(obj, 5.0)
    worst = 0.0
    for _ in range(30):
        verdict = monitor.check(truth, world.perceive(reference=truth).configuration)
        worst = max(worst, verdict.max_error)
        assert not verdict.fired
    assert 0.0 < worst < 5.0  # noise is there, but well below the threshold


def test_goal_and_tip_link_thresholds() -> None:
    obj = ArticulatedObject(4)  # goal link L3; L4 is tip-ward of every goal link
    pred = random_configuration(4, random.Random(1)).with_angle(4, "z-axis", 90.0)
    m = Monitor(obj, 8.0, goal_links=("L3",), other_threshold_deg=45.0, tip_links=False)
    assert m.thresholds[1:] == (45.0, 8.0, float("inf"))
    assert not m.check(pred, pred.with_angle(4, "z-axis", 150.0)).fired
    assert m.check(pred, pred.with_angle(2, "z-axis", pred.gamma[1] + 50.0)).fired


def test_canonical_keeps_directions_and_puts_gamma_in_upper_half() -> None:
    conf = random_configuration(6, random.Random(9))
    can = canonical(conf)
    assert np.all(direction_error(conf, can) < 1e-9)
    assert all(0.0 <= g <= 180.0 for g in can.gamma)


def test_fit_fall_recovers_speed_and_acceleration() -> None:
    t = np.linspace(0.0, 4.0, 41)
    speed, _ = fit_fall(t, 90.0 - 0.7 * t)
    _, acc = fit_fall(t, 90.0 - 0.5 * 2.0 * t**2)
    assert speed == pytest.approx(0.7)
    assert acc == pytest.approx(2.0)
