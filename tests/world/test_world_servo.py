"""The pose servo: integral action that tracks, bounded so a blocked hand cannot wind it up."""

from __future__ import annotations

import numpy as np

from artiplan.world.rotations import quat_axis_angle
from artiplan.world.servo import Servo, ServoGains

IDENTITY = np.array([1.0, 0.0, 0.0, 0.0])


def test_a_small_steady_error_integrates_as_without_a_bound() -> None:
    servo = Servo(ServoGains(kp=1.0, ki=10.0))
    desired = (np.array([0.001, 0.0, 0.0]), IDENTITY)
    actual = (np.zeros(3), IDENTITY)
    for _ in range(100):  # 1 s at 10 ms
        servo.command(desired, actual, 0.01)
    # ki * e * t = 10 * 1 mm * 1 s = 10 mm, well inside the 40 mm bound.
    assert np.allclose(servo.int_pos, [0.010, 0.0, 0.0], atol=1e-9)


def test_a_blocked_hand_does_not_wind_the_integrals_up() -> None:
    gains = ServoGains(kp=1.0, ki=10.0)
    servo = Servo(gains)
    # The link is held 20 cm and 90 deg away from where it should be, for 10 s.
    desired = (np.array([0.0, 0.2, 0.0]), quat_axis_angle(np.array([0.0, 0.0, 1.0]), np.pi / 2))
    actual = (np.zeros(3), IDENTITY)
    for _ in range(1000):
        pos, quat = servo.command(desired, actual, 0.01)
    assert np.linalg.norm(servo.int_pos) <= gains.max_int_pos + 1e-12
    assert np.linalg.norm(servo.int_rot) <= gains.max_int_rot + 1e-12
    # The bound keeps the direction of the error: +y and about +z.
    assert servo.int_pos[1] > 0.99 * gains.max_int_pos
    assert servo.int_rot[2] > 0.99 * gains.max_int_rot
    # The command overshoots the desired pose by at most the bound plus the P term.
    assert np.linalg.norm(pos - desired[0]) <= gains.max_int_pos + gains.kp * 0.2 + 1e-9
