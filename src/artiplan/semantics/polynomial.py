"""Polynomials in elapsed time ``dt`` [s], as tuples of coefficients, lowest degree first.

``(c0, c1, c2)`` is ``c0 + c1*dt + c2*dt**2``. Roots of degree <= 2 are computed in closed form
(the numerically stable quadratic formula); higher degrees with ``numpy.roots`` polished by
Newton steps.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

Poly = tuple[float, ...]

#: Imaginary parts below this (relative to the root's size) count as real (numpy roots).
_IMAG_TOL = 1e-7


def trim(p: Sequence[float]) -> Poly:
    """Drop zero leading (highest-degree) coefficients; the zero polynomial is ``(0.0,)``."""
    n = len(p)
    while n > 1 and p[n - 1] == 0.0:
        n -= 1
    return tuple(p[:n]) if n else (0.0,)


def add(a: Poly, b: Poly) -> Poly:
    n = max(len(a), len(b))
    return trim([(a[i] if i < len(a) else 0.0) + (b[i] if i < len(b) else 0.0) for i in range(n)])


def neg(a: Poly) -> Poly:
    return tuple(-c for c in a)


def sub(a: Poly, b: Poly) -> Poly:
    return add(a, neg(b))


def mul(a: Poly, b: Poly) -> Poly:
    out = [0.0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        if x == 0.0:
            continue
        for j, y in enumerate(b):
            out[i + j] += x * y
    return trim(out)


def scale(a: Poly, k: float) -> Poly:
    return trim([c * k for c in a])


def integrate(p: Poly, c0: float) -> Poly:
    """The antiderivative of ``p`` whose value at dt = 0 is ``c0``."""
    return trim([c0, *(c / (i + 1) for i, c in enumerate(p))])


def derivative(p: Poly) -> Poly:
    return trim([i * c for i, c in enumerate(p)][1:]) if len(p) > 1 else (0.0,)


def value(p: Poly, dt: float) -> float:
    """``p(dt)`` by Horner's rule."""
    acc = 0.0
    for c in reversed(p):
        acc = acc * dt + c
    return acc


def shift(p: Poly, t0: float) -> Poly:
    """The polynomial ``q(dt) = p(t0 + dt)`` (Taylor coefficients of ``p`` at ``t0``)."""
    out = list(p)
    n = len(out)
    # Repeated synthetic division (Horner) gives the Taylor coefficients at t0.
    for k in range(n - 1):
        for i in range(n - 2, k - 1, -1):
            out[i] += t0 * out[i + 1]
    return trim(out)


def sign_after(p: Poly, zero_tol: float) -> int:
    """Sign of ``p`` just after dt = 0 (``-1``, ``0`` or ``1``).

    ``p(0)`` within ``zero_tol`` of 0 counts as 0; the sign is then that of the first non-zero
    higher coefficient (the first non-vanishing derivative). ``0``: identically zero.
    """
    if abs(p[0]) > zero_tol:
        return 1 if p[0] > 0 else -1
    for c in p[1:]:
        if c != 0.0:
            return 1 if c > 0 else -1
    return 0


def positive_roots(p: Poly, horizon: float = math.inf, zero_tol: float = 0.0) -> list[float]:
    """Real roots ``r`` of ``p`` with ``0 < r <= horizon``, ascending, duplicates merged.

    A constant-term within ``zero_tol`` of 0 is taken as exactly 0 (the root at dt = 0 is
    then factored out), so rounding noise does not produce spurious roots at dt ~ 1e-15.
    """
    p = trim(p)
    if abs(p[0]) <= zero_tol:
        p = trim(p[1:]) if len(p) > 1 else (0.0,)  # divide by dt
        while len(p) > 1 and p[0] == 0.0:
            p = p[1:]
    deg = len(p) - 1
    if deg <= 0:
        return []
    if deg == 1:
        roots = [-p[0] / p[1]]
    elif deg == 2:
        roots = _quadratic(p[0], p[1], p[2])
    else:
        roots = _numpy_roots(p)
    out = sorted(r for r in roots if 0.0 < r <= horizon)
    merged: list[float] = []
    for r in out:
        if not merged or r - merged[-1] > 1e-12 * max(1.0, r):
            merged.append(r)
    return merged


def _quadratic(c: float, b: float, a: float) -> list[float]:
    """Real roots of ``a x^2 + b x + c`` (a != 0), stable form (no cancellation)."""
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        # A touching root lost to rounding: treat tiny negative discriminants as zero.
        if -disc > 1e-12 * (b * b + abs(4.0 * a * c)):
            return []
        disc = 0.0
    sq = math.sqrt(disc)
    q = -0.5 * (b + math.copysign(sq, b))
    if q == 0.0:
        return [0.0]
    return [q / a, c / q]


def _numpy_roots(p: Poly) -> list[float]:
    import numpy as np  # only for degree >= 3

    raw = np.roots(list(reversed(p)))
    out = []
    for z in raw:
        if abs(z.imag) <= _IMAG_TOL * max(1.0, abs(z.real)):
            out.append(_polish(p, float(z.real)))
    return out


def _polish(p: Poly, x: float, steps: int = 3) -> float:
    """A few Newton steps on ``p`` from ``x`` (kept only while they improve |p|)."""
    dp = derivative(p)
    for _ in range(steps):
        d = value(dp, x)
        if d == 0.0:
            break
        y = x - value(p, x) / d
        if abs(value(p, y)) >= abs(value(p, x)):
            break
        x = y
    return x
