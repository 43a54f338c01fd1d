"""A pose servo: drives a hand so that the link it holds reaches a desired pose."""

from __future__ import annotations

from dataclasses import dataclass

import mujoco
import numpy as np

from artiplan.world.rotations import Vec, quat_axis_angle, quat_conj, quat_mul


@dataclass(frozen=True)
class ServoGains:
    """Gains of the pose servo that drives each hand so its link reaches the desired pose.

    A grasp is a soft weld and the joints are damped, so commanding the desired pose alone
    leaves a steady lag (degrees for the stiff preset); the servo adds a proportional and an
    integral correction of the link's pose error to the command (a robot's tracking loop).

    The integral gain is bounded by stability: the rotating hand's servo follows a moving
    reference through a soft weld and damped joints, and with ki = 40 it oscillated with
    growing amplitude in 6 of 24 random 6-link turns (10 of 24 on 12 links; a held link shook
    by +-30 deg within 3 s of a turn's start). ki = 10 oscillated in none of 96 random turns
    on 4-12 links and follows the turn to 0.02-0.09 deg mean on 4-8 links.

    The integrals are bounded (anti-windup): a hand that cannot follow (an arm at a joint
    limit or held by a contact) otherwise winds them up without end; in one 6-link Baxter run
    they reached 542 mm / 263 deg, and the command then threw MuJoCo into divergence. In
    the 6-link Baxter runs measured then they stayed below 27 mm / 17.5 deg (below 3 mm /
    6 deg on 4 links), so the default bounds sat above what tracking needs; since arm contacts
    stop turns (session 21) about one 6-link turn per task reaches a bound, mostly the 40 mm
    one (``WorldConfig.strain_stop`` counted 21 in 20 tasks).

    Attributes:
        kp: Proportional gain [-].
        ki: Integral gain [1/s].
        max_int_pos: Bound on the norm of the position integral [m].
        max_int_rot: Bound on the norm of the rotation integral [rad].
    """

    kp: float = 2.0
    ki: float = 10.0
    max_int_pos: float = 0.04
    max_int_rot: float = float(np.radians(25.0))


class Servo:
    """Per-hand pose servo: command = correction * desired (see :class:`ServoGains`)."""

    def __init__(self, gains: ServoGains) -> None:
        self.gains = gains
        self.int_rot = np.zeros(3)
        self.int_pos = np.zeros(3)

    def command(
        self, desired: tuple[Vec, Vec], actual: tuple[Vec, Vec], dt: float
    ) -> tuple[Vec, Vec]:
        """(position, quaternion) to command given the desired and actual link poses."""
        p_d, q_d = desired
        p_a, q_a = actual
        q_err = np.empty(4)
        mujoco.mju_mulQuat(q_err, q_d, quat_conj(q_a))
        e_rot = np.empty(3)
        mujoco.mju_quat2Vel(e_rot, q_err, 1.0)
        e_pos = p_d - p_a
        g = self.gains
        self.int_rot = _bounded(self.int_rot + g.ki * e_rot * dt, g.max_int_rot)
        self.int_pos = _bounded(self.int_pos + g.ki * e_pos * dt, g.max_int_pos)
        corr = self.int_rot + g.kp * e_rot
        angle = float(np.linalg.norm(corr))
        q_corr = quat_axis_angle(corr, angle) if angle > 1e-12 else np.array([1.0, 0, 0, 0])
        return p_d + self.int_pos + g.kp * e_pos, quat_mul(q_corr, q_d)


def _bounded(v: Vec, limit: float) -> Vec:
    """``v`` scaled down so its norm is at most ``limit`` (direction kept)."""
    n = float(np.linalg.norm(v))
    return v * (limit / n) if n > limit else v
