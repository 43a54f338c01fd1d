"""Angle arithmetic in degrees, with the wrap-around the PDDL+ models use."""

from __future__ import annotations

import math


def wrap_deg(angle: float) -> float:
    """Map ``angle`` [deg] into [0, 360)."""
    a = math.fmod(angle, 360.0)
    if a < 0.0:
        a += 360.0
    # fmod of a tiny negative number can round up to exactly 360.
    return 0.0 if a >= 360.0 else a


def signed_delta_deg(a: float, b: float) -> float:
    """Shortest signed rotation [deg] that takes angle ``a`` to angle ``b``, in [-180, 180)."""
    return (b - a + 180.0) % 360.0 - 180.0


def in_window_deg(angle: float, centre: float, half_width: float) -> bool:
    """True when ``angle`` is within ``half_width`` [deg] of ``centre`` across the 0/360 wrap."""
    return abs(signed_delta_deg(centre, angle)) <= half_width
