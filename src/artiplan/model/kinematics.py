"""Forward kinematics and direction-angle errors."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from artiplan.model.configuration import Configuration
from artiplan.model.obj import ArticulatedObject


def direction(theta: float, gamma: float) -> NDArray[np.float64]:
    """Unit vector of a link, base end -> tip end, from its angles [deg].

    u = (sin g cos t, sin g sin t, -cos g): gamma = 0 points straight down.
    """
    t, g = math.radians(theta), math.radians(gamma)
    return np.array([math.sin(g) * math.cos(t), math.sin(g) * math.sin(t), -math.cos(g)])


def directions(conf: Configuration) -> NDArray[np.float64]:
    """(n, 3) array of link unit vectors."""
    return np.array([direction(t, g) for t, g in zip(conf.theta, conf.gamma, strict=True)])


def forward_kinematics(obj: ArticulatedObject, conf: Configuration) -> NDArray[np.float64]:
    """(n + 1, 3) points [m]: the base end of L1, every joint, and the tip of Ln."""
    if conf.n_links != obj.n_links:
        raise ValueError(f"object has {obj.n_links} links, configuration {conf.n_links}")
    steps = directions(conf) * obj.link_length
    points = np.zeros((obj.n_links + 1, 3))
    points[0] = obj.base_position
    points[1:] = np.asarray(obj.base_position) + np.cumsum(steps, axis=0)
    return points


def direction_error(a: Configuration, b: Configuration) -> NDArray[np.float64]:
    """Angle [deg] between the direction vectors of each link in ``a`` and ``b``.

    This is the only error measure artiplan uses between configurations: it is blind to the
    double cover and to theta at the poles, as a camera is.
    """
    if a.n_links != b.n_links:
        raise ValueError(f"configurations differ in size: {a.n_links} vs {b.n_links}")
    return _angles(directions(a), directions(b))


def relative_turn(then: Configuration, now: Configuration, link: int, other: int) -> float:
    """How far [deg] link ``link`` turned against link ``other`` (1-based indices) from
    ``then`` to ``now``: the change of the angle between their directions, or, against the
    clamped base L1 (``other`` 1, which stands for the fixed scene too), the angle between
    ``link``'s own directions then and now. Links carried together by one turn have not
    turned against each other; a turn of ``link`` about ``other``'s axis is not seen (the
    links' directions fix no frame about them)."""
    if other == 1:
        return float(direction_error(then, now)[link - 1])
    u_then, u_now = directions(then), directions(now)
    return abs(float(_angles(u_now[link - 1], u_now[other - 1]))
               - float(_angles(u_then[link - 1], u_then[other - 1])))


def _angles(u: NDArray[np.float64], v: NDArray[np.float64]) -> NDArray[np.float64]:
    """Angle [deg] between unit vectors ``u`` and ``v`` (along the last axis: row by row)."""
    return np.degrees(np.arccos(np.clip(np.sum(u * v, axis=-1), -1.0, 1.0)))
