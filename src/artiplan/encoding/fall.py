"""Per-link fall-speed factors for UCM (``EncodingOptions.fall = "torque"``), plain geometry.

UCM turns every free link toward rest at one speed, ``speed-g``. The physics world's joints are
overdamped, with the damping of joint j scaled by c_j**2 (c_j: links tip-ward of joint j, itself
included; :mod:`artiplan.world.presets`), so joint j turns at ``tau_j / (d c_j**2)``: the
gravity torque of its whole subchain, not of its own link. A straight subchain held horizontal
turns at the reference speed ``m g L / (2 d)`` whatever its length (what ``speed-g`` is
calibrated on); a folded one, or one whose links hang near rest, much more slowly, and one whose
centre of mass lies across the joint from the link turns the other way.

The factor of link j is its joint's rate toward rest (the link's own gamma, toward 0) divided by
the reference speed, from the geometry alone (equal links, mass at their middles, unit mass and
gravity: both cancel), clipped to [:data:`FALL_MIN`, 1]. The encoding multiplies ``speed-g``
by it in link j's gravity processes (and in what they carry). Like the ``projected`` carry
factors it is fixed at the problem's start, so it is a first-order prediction for the time
right after it: the closed loop re-plans from each new percept.
"""

from __future__ import annotations

import math

import numpy as np

from artiplan.model import ArticulatedObject, Configuration
from artiplan.model.kinematics import forward_kinematics

#: Smallest factor: a link whose subchain turns it away from rest (or not at all) is still
#: given a slow fall, so that the planner's gravity processes keep a positive speed.
FALL_MIN = 0.02
#: Below this sine of gamma the rate of gamma is ill-defined (the link points straight down
#: or up): the factor is then the size of the joint's rate, not its gamma component.
POLE_SIN = 1e-3


def fall_factors(obj: ArticulatedObject, conf: Configuration) -> tuple[float, ...]:
    """Fall-speed factor [1] of every link, base to tip (L1's is 1: it is clamped anyway).

    See the module docstring: ``clip(rate_toward_rest / reference_rate, FALL_MIN, 1)``.
    """
    points = forward_kinematics(obj, conf)
    n = obj.n_links
    half = obj.link_length / 2.0
    mids = (points[:-1] + points[1:]) / 2.0
    down = np.array([0.0, 0.0, -1.0])
    out = [1.0]
    for j in range(1, n):
        torque = np.cross(mids[j:] - points[j], down).sum(axis=0)  # unit mass and gravity
        omega = torque / float((n - j) ** 2)  # joint j's damping grows as c**2
        u = (points[j + 1] - points[j]) / obj.link_length
        du = np.cross(omega, u)
        sin_g = math.sqrt(max(0.0, 1.0 - float(u[2]) ** 2))
        # d(gamma)/dt is du_z / sin(gamma); toward rest is minus that.
        rate = float(np.linalg.norm(du)) if sin_g < POLE_SIN else -float(du[2]) / sin_g
        out.append(min(1.0, max(FALL_MIN, rate / half)))
    return tuple(out)
