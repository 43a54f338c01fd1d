"""The rotation a grasp pair must serve: which link turns, about which axis, how far.

:class:`Turn` is what :meth:`artiplan.world.scene.World.hold_and_rotate` knows before the
hands choose their grasps: the rotated link's joint (the pivot), the axis with the rotation's
sense, and the extent to check. The grasp choice turns the rotating hand's grasp pose about
it every :data:`STEP_DEG` (:func:`turned_pose`), and the rotated link with every link tip-ward
of it (:func:`turned_joint`), and checks both arms there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mujoco
import numpy as np

from artiplan.world.rotations import Vec, quat_axis_angle, quat_conj, quat_mul, quat_to_mat

#: The rotation is checked at every this many degrees of the turn.
STEP_DEG = 1.0
#: Extent [deg] checked when the plan does not say how far the turn goes.
DEFAULT_EXTENT_DEG = 30.0
#: Extra extent [deg] checked past the planned one (the servo overshoots a little).
EXTRA_DEG = 3.0


@dataclass(frozen=True)
class Turn:
    """A rotation of link ``link`` (1-based index) about ``axis`` (unit, world frame, its
    sense the rotation's) through ``pivot`` [m] (the link's base-end joint), checked up to
    ``degrees`` [deg]."""

    link: int
    axis: Vec
    pivot: Vec
    degrees: float = DEFAULT_EXTENT_DEG

    def steps(self) -> list[float]:
        """Angles [deg] checked: every STEP_DEG up to the extent (the extent included)."""
        n = max(1, math.ceil(self.degrees / STEP_DEG))
        return [self.degrees * i / n for i in range(1, n + 1)]

    def quat(self, degrees: float) -> Vec:
        return quat_axis_angle(self.axis, math.radians(degrees))


def turned_pose(turn: Turn, degrees: float, pos: Vec, quat: Vec) -> tuple[Vec, Vec]:
    """A world pose (position [m], wxyz) carried ``degrees`` along ``turn``."""
    q = turn.quat(degrees)
    return turn.pivot + quat_to_mat(q) @ (pos - turn.pivot), quat_mul(q, quat)


def turned_joint(
    model: mujoco.MjModel, data: mujoco.MjData, turn: Turn, degrees: float
) -> tuple[int, Vec]:
    """(qpos address, quaternion) of the rotated link's ball joint that turns it (and the
    links it carries, rigidly) ``degrees`` along ``turn`` from where ``data`` has it."""
    body = model.body(f"L{turn.link}").id
    parent = model.body(f"L{turn.link - 1}").id
    new_abs = quat_mul(turn.quat(degrees), data.xquat[body])
    rel = quat_mul(quat_conj(data.xquat[parent]), new_abs)
    adr = int(model.jnt_qposadr[model.joint(f"J{turn.link}").id])
    out = quat_mul(quat_conj(model.body_quat[body]), rel)
    return adr, out / np.linalg.norm(out)
