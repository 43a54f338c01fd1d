"""Rotations for link frames: (theta, gamma) <-> quaternions, and the double-cover choice.

A link body's frame has its origin at the link's base-end joint and its local -z axis along the
link (base end -> tip end), so the identity orientation hangs straight down (gamma = 0).
Quaternions are MuJoCo's (w, x, y, z). Angles in degrees unless a name says radians.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from artiplan.model import HORIZONTAL_PLANE, VERTICAL_PLANE, Configuration, direction, wrap_deg
from artiplan.model.angles import signed_delta_deg

Vec = NDArray[np.float64]

#: Below this sin(gamma) theta is not observable (a pole): keep the reference's theta.
POLE_SIN = 1e-6


def quat_mul(a: Vec, b: Vec) -> Vec:
    """Hamilton product a * b."""
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return np.array(
        [
            w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2,
            w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
            w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2,
        ]
    )


def quat_conj(q: Vec) -> Vec:
    """Inverse of a unit quaternion."""
    return np.array([q[0], -q[1], -q[2], -q[3]])


def quat_axis_angle(axis: Vec, angle_rad: float) -> Vec:
    """Rotation by ``angle_rad`` about the unit vector ``axis``."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    s = math.sin(angle_rad / 2.0)
    return np.array([math.cos(angle_rad / 2.0), a[0] * s, a[1] * s, a[2] * s])


def quat_to_mat(q: Vec) -> Vec:
    """3x3 rotation matrix of a unit quaternion."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def rotate(q: Vec, v: Vec) -> Vec:
    """Vector ``v`` rotated by the unit quaternion ``q``."""
    return quat_to_mat(q) @ np.asarray(v, dtype=float)


def link_quat(theta: float, gamma: float) -> Vec:
    """World orientation of a link frame with angles (theta, gamma) [deg].

    R = Rz(theta) Ry(-gamma): maps the frame's -z axis onto direction(theta, gamma).
    """
    qz = quat_axis_angle(np.array([0.0, 0.0, 1.0]), math.radians(theta))
    qy = quat_axis_angle(np.array([0.0, 1.0, 0.0]), -math.radians(gamma))
    return quat_mul(qz, qy)


def angles_of(u: Vec) -> tuple[float, float]:
    """(theta, gamma) [deg] of a direction, gamma in [0, 180] (one of the two covers)."""
    u = np.asarray(u, dtype=float) / np.linalg.norm(u)
    gamma = math.degrees(math.acos(max(-1.0, min(1.0, -u[2]))))
    theta = wrap_deg(math.degrees(math.atan2(u[1], u[0])))
    return theta, gamma


def nearest_cover(u: Vec, ref_theta: float, ref_gamma: float) -> tuple[float, float]:
    """Angles of direction ``u`` in the double-cover representation nearest a reference.

    The two candidates are (t, g) and (t + 180, 360 - g); the distance is the sum of the
    wrapped angle differences. At a pole theta is unobservable and the reference's is kept.
    """
    t, g = angles_of(u)
    u = np.asarray(u, dtype=float) / np.linalg.norm(u)
    if math.hypot(u[0], u[1]) < POLE_SIN:
        t = wrap_deg(ref_theta)
    candidates = [(t, g), (wrap_deg(t + 180.0), wrap_deg(360.0 - g))]

    def dist(c: tuple[float, float]) -> float:
        return abs(signed_delta_deg(ref_theta, c[0])) + abs(signed_delta_deg(ref_gamma, c[1]))

    return min(candidates, key=dist)


def configuration_from_directions(
    dirs: Vec, reference: Configuration | None = None
) -> Configuration:
    """A configuration with the given (n, 3) link directions, covers chosen near ``reference``."""
    thetas, gammas = [], []
    for i, u in enumerate(dirs):
        if reference is not None:
            t, g = nearest_cover(u, reference.theta[i], reference.gamma[i])
        else:
            t, g = angles_of(u)
        thetas.append(t)
        gammas.append(g)
    return Configuration(tuple(thetas), tuple(gammas))


def rotation_axis(plane: str, theta: float) -> Vec:
    """World axis about which rotating a link *increases* its angle on ``plane``.

    ``xy-axes``: the world vertical (+z, counter-clockwise seen from above increases theta).
    ``z-axis``: the horizontal normal of the link's vertical plane, (sin t, -cos t, 0), which
    increases gamma (d u / d gamma = axis x u).
    """
    if plane == HORIZONTAL_PLANE:
        return np.array([0.0, 0.0, 1.0])
    if plane == VERTICAL_PLANE:
        t = math.radians(theta)
        return np.array([math.sin(t), -math.cos(t), 0.0])
    raise ValueError(f"unknown plane {plane!r}")


__all__ = [
    "angles_of",
    "configuration_from_directions",
    "direction",
    "link_quat",
    "nearest_cover",
    "quat_axis_angle",
    "quat_conj",
    "quat_mul",
    "quat_to_mat",
    "rotate",
    "rotation_axis",
]
