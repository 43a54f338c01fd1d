"""Forward kinematics, the double cover and direction errors."""

from __future__ import annotations

import random

import numpy as np
import pytest

from artiplan.model import (
    ArticulatedObject,
    Configuration,
    direction,
    direction_error,
    forward_kinematics,
    random_configuration,
)


@pytest.mark.parametrize(
    ("theta", "gamma", "expected"),
    [
        (0.0, 0.0, (0.0, 0.0, -1.0)),  # hanging straight down
        (0.0, 180.0, (0.0, 0.0, 1.0)),  # straight up
        (0.0, 90.0, (1.0, 0.0, 0.0)),  # horizontal along +x
        (90.0, 90.0, (0.0, 1.0, 0.0)),  # horizontal along +y (counter-clockwise from +x)
        (180.0, 90.0, (-1.0, 0.0, 0.0)),
        (45.0, 45.0, (0.5, 0.5, -np.sqrt(0.5))),
    ],
)
def test_direction_of_known_angles(theta: float, gamma: float, expected: tuple) -> None:
    np.testing.assert_allclose(direction(theta, gamma), expected, atol=1e-12)


def test_forward_kinematics_known_points() -> None:
    obj = ArticulatedObject(3, link_length=0.15, base_position=(1.0, 2.0, 3.0))
    # L1 horizontal along +x, L2 horizontal along +y, L3 straight up.
    conf = Configuration.from_angles([0, 90, 0], [90, 90, 180])
    points = forward_kinematics(obj, conf)
    expected = [
        (1.0, 2.0, 3.0),
        (1.15, 2.0, 3.0),
        (1.15, 2.15, 3.0),
        (1.15, 2.15, 3.15),
    ]
    np.testing.assert_allclose(points, expected, atol=1e-12)


def test_hanging_object_points_straight_down() -> None:
    obj = ArticulatedObject(4)
    points = forward_kinematics(obj, Configuration.hanging(4))
    np.testing.assert_allclose(points[:, 2], [0.0, -0.15, -0.30, -0.45, -0.60], atol=1e-12)
    np.testing.assert_allclose(points[:, :2], 0.0, atol=1e-12)


def test_double_cover_gives_the_same_points() -> None:
    obj = ArticulatedObject(6)
    conf = random_configuration(6, random.Random(7))
    other = Configuration(
        tuple(t + 180.0 for t in conf.theta), tuple(360.0 - g for g in conf.gamma)
    ).wrapped()
    assert other.theta != conf.theta  # a different representation ...
    np.testing.assert_allclose(
        forward_kinematics(obj, conf), forward_kinematics(obj, other), atol=1e-12
    )  # ... of the same shape
    np.testing.assert_allclose(direction_error(conf, other), 0.0, atol=1e-5)


def test_direction_error_known_values() -> None:
    a = Configuration.from_angles([0, 0, 0], [0, 90, 90])
    b = Configuration.from_angles([123, 90, 0], [0, 90, 180])
    # L1: both hang (theta unobservable at the pole) -> 0; L2: +x vs +y -> 90; L3: +x vs up -> 90.
    np.testing.assert_allclose(direction_error(a, b), [0.0, 90.0, 90.0], atol=1e-9)
    c = Configuration.from_angles([0, 0, 0], [0, 0, 180])
    assert direction_error(a, c)[2] == pytest.approx(90.0)
    assert direction_error(Configuration.hanging(3), c)[2] == pytest.approx(180.0)


def test_direction_error_rejects_different_sizes() -> None:
    with pytest.raises(ValueError, match="differ in size"):
        direction_error(Configuration.hanging(3), Configuration.hanging(4))
