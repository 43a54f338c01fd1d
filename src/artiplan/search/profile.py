"""The least time of a double integrator: a position ``x`` whose rate is a speed ``w``, the
speed's rate set by a control level (one to speed up, one to brake).

- :class:`Rate`: the speed's rate at one level as a function of the speed: a constant (a
  linear car), or a table of the times and distances between speeds when it depends on the
  speed (drag: ``w' = a - c w^2`` creeps up to a terminal speed, coasting never quite stops);
- :func:`point_time`: the closed form for constant rates (bang-bang with one switch, a cruise
  at a speed cap);
- :func:`profile`: the same for any two rates, by bisection on the switching speed;
- :func:`box_profile`: into a box of positions with the speed in a band.

Every profile says how long its first phase lasts: how long the control may stay as it is.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from artiplan.records import dataclass

#: Accelerations below this [1/s^2] count as none (the speed can only cruise).
FLOOR = 1e-9
#: Cells of a rate table.
CELLS = 128


@dataclass(frozen=True, slots=True)
class Profile:
    """A bang-bang profile: its time [s], whether it accelerates first, and how long [s] its
    first phase lasts (until the control must change: the switch, or the start of a cruise
    at a cap the control does not hold by itself)."""

    time: float
    up: bool
    first: float


NONE = Profile(math.inf, True, 0.0)


def point_time(dist: float, y0: float, yf: float, al: float, be: float,
               vhi: float = math.inf, vlo: float = -math.inf) -> Profile:
    """The least-time profile that moves ``dist`` and changes the speed from ``y0`` to
    ``yf``, with the speed's rate in [-be, al] (al, be >= 0) and the speed within [vlo, vhi]
    (a cruise at a cap). Bang-bang with one switch: accelerate then brake (a peak), or brake
    then accelerate (a valley, through reverse if need be); time inf if neither exists."""
    al, be = max(al, FLOOR), max(be, FLOOR)
    best = _peak(dist, y0, yf, al, be, vhi, True)
    # A valley is the peak of the mirrored motion (positions, speeds and rates negated).
    down = _peak(-dist, -y0, -yf, be, al, -vlo, False)
    return down if down.time < best.time else best


def _peak(dist: float, y0: float, yf: float, al: float, be: float, vhi: float,
          up: bool) -> Profile:
    """Accelerate (rate ``al``), then brake (``be``), peaking at or above both end speeds,
    cruising at ``vhi`` if the peak would pass it; ``up`` labels the profile."""
    s2 = (2.0 * al * be * dist + be * y0 * y0 + al * yf * yf) / (al + be)
    top = max(y0, yf)
    if s2 < 0.0:
        return NONE
    s = math.sqrt(s2)
    vp = -s if -s >= top - 1e-12 else s if s >= top - 1e-12 else None
    if vp is None:
        return NONE
    if vp > vhi >= top and vhi > 0.0:
        cruise = (dist - (vhi * vhi - y0 * y0) / (2 * al)
                  - (vhi * vhi - yf * yf) / (2 * be)) / vhi
        rise = (vhi - y0) / al
        return Profile(rise + (vhi - yf) / be + cruise, up, rise)
    return Profile((vp - y0) / al + (vp - yf) / be, up, (vp - y0) / al)


class Rate:
    """The speed's rate at one control level, as a function of the speed (the rest fixed):
    ``const`` if it does not depend on the speed, else tabulated on [lo, hi] (beyond it, the
    rate at the nearer end). A cell where the rate changes sign or vanishes is a wall: a
    speed the level never takes the speed past (drag's terminal speed)."""

    def __init__(self, fn: Callable[[float], float], lo: float, hi: float) -> None:
        probes = [fn(lo + (hi - lo) * k / 4.0) for k in range(5)]
        self.const: float | None = None
        if max(probes) - min(probes) <= 1e-12 * max(1.0, max(map(abs, probes))):
            self.const = probes[0]
            return
        self.lo, self.hi, self.step = lo, hi, (hi - lo) / CELLS
        self.speeds = [lo + k * self.step for k in range(CELLS + 1)]
        self.rates = [fn(s) for s in self.speeds]
        # per cell: its integrals of 1/f (time) and s/f (distance), trapezoidal; prefix sums
        # over the cells that are not walls, and a count of the walls
        self.ok: list[bool] = []
        self.pt, self.pd, self.walls = [0.0], [0.0], [0]
        for k in range(CELLS):
            f0, f1 = self.rates[k], self.rates[k + 1]
            ok = f0 * f1 > 0.0 and min(abs(f0), abs(f1)) > FLOOR
            self.ok.append(ok)
            s0, s1 = self.speeds[k], self.speeds[k + 1]
            self.pt.append(self.pt[-1] + (0.5 * self.step * (1.0 / f0 + 1.0 / f1) if ok else 0.0))
            self.pd.append(self.pd[-1] + (0.5 * self.step * (s0 / f0 + s1 / f1) if ok else 0.0))
            self.walls.append(self.walls[-1] + (0 if ok else 1))

    def at(self, w: float) -> float:
        """The rate at speed ``w`` (the nearest tabulated speed)."""
        if self.const is not None:
            return self.const
        return self.rates[min(CELLS, max(0, round((w - self.lo) / self.step)))]

    def _cell(self, w: float) -> int:
        return min(CELLS - 1, max(0, int((w - self.lo) / self.step)))

    def _wall(self, k: int, up: bool) -> float:
        """Where a speed entering wall cell ``k`` going ``up`` (or down) stops: the rate's zero
        between its ends (linear), the entry end if the rate there does not push that way."""
        e = k if up else k + 1
        f_in, f_out = self.rates[e], self.rates[k + 1 if up else k]
        sign = 1.0 if up else -1.0
        if f_in * sign <= FLOOR:
            return self.speeds[e]
        frac = f_in / (f_in - f_out) if f_in != f_out and f_in * f_out <= 0.0 else 1.0
        return self.speeds[e] + sign * frac * self.step

    def _piece(self, k: int, x: float, y: float, up: bool) -> tuple[float, float]:
        """Integrals over [x, y] inside cell ``k`` (x <= y), travelled up or down."""
        if self.ok[k]:
            r = (y - x) / self.step
            return r * (self.pt[k + 1] - self.pt[k]), r * (self.pd[k + 1] - self.pd[k])
        stop = self._wall(k, up)
        if (up and y > stop + 1e-12) or (not up and x < stop - 1e-12):
            return math.nan, math.nan
        f = self.rates[k if up else k + 1]
        return (y - x) / f, (y * y - x * x) / (2.0 * f)

    def _integral(self, a: float, b: float, up: bool) -> tuple[float, float]:
        """Integrals of (1/f, s/f) over [a, b] (a <= b) within the table."""
        ca, cb = self._cell(a), self._cell(b)
        if ca == cb:
            return self._piece(ca, a, b, up)
        if self.walls[cb] - self.walls[ca + 1]:
            return math.nan, math.nan  # a wall in between
        t1, d1 = self._piece(ca, a, self.speeds[ca + 1], up)
        t2, d2 = self._piece(cb, self.speeds[cb], b, up)
        return (t1 + t2 + self.pt[cb] - self.pt[ca + 1],
                d1 + d2 + self.pd[cb] - self.pd[ca + 1])

    def between(self, v1: float, v2: float) -> tuple[float, float]:
        """(time [s], distance) to take the speed from ``v1`` to ``v2`` at this level; time inf
        if the rate does not lead there."""
        if v1 == v2:
            return 0.0, 0.0
        if self.const is not None:
            f = self.const
            if (v2 - v1) * f <= 0.0 or abs(f) <= FLOOR:
                return math.inf, math.nan
            return (v2 - v1) / f, (v2 * v2 - v1 * v1) / (2.0 * f)
        up = v2 > v1
        a, b = (v1, v2) if up else (v2, v1)
        t = d = 0.0
        for f, lo, hi in ((self.rates[0], a, min(b, self.lo)),
                          (self.rates[CELLS], max(a, self.hi), b)):
            if hi > lo:  # beyond the table: the end's rate, constant
                if abs(f) <= FLOOR:
                    return math.inf, math.nan
                t, d = t + (hi - lo) / f, d + (hi * hi - lo * lo) / (2.0 * f)
        lo, hi = max(a, self.lo), min(b, self.hi)
        if hi > lo:
            ti, di = self._integral(lo, hi, up)
            t, d = t + ti, d + di
        if not up:
            t, d = -t, -d
        if t != t or t <= 0.0:
            return math.inf, math.nan
        return t, d

    def reach(self, w: float, up: bool) -> float:
        """How far this level takes the speed from ``w`` up (``up``) or down: where its rate
        stops pushing that way (+-inf: never)."""
        sign = 1.0 if up else -1.0
        if self.const is not None:
            return sign * math.inf if self.const * sign > FLOOR else w
        if self.at(w) * sign <= FLOOR:
            return w
        if not self.lo <= w <= self.hi:
            return sign * math.inf  # beyond the table the rate is the end's, constant
        k = self._cell(w)
        for i in (range(k, CELLS) if up else range(k, -1, -1)):
            if not self.ok[i]:
                return max(w, self._wall(i, up)) if up else min(w, self._wall(i, up))
        return sign * math.inf


def profile(dist: float, y0: float, yf: float, up: Rate, down: Rate,
            vhi: float = math.inf, vlo: float = -math.inf) -> Profile:
    """The least-time profile with ``up``'s level first then ``down``'s (a peak), or the
    other way round (a valley), for any rates (:func:`point_time` when both are constant):
    the switching speed by bisection, a cruise at a cap or where a level stops pushing (the
    level holds that cruise by itself: drag's terminal speed)."""
    if up.const is not None and down.const is not None and up.const >= -FLOOR \
            and down.const <= FLOOR:
        return point_time(dist, y0, yf, max(up.const, 0.0), max(-down.const, 0.0), vhi, vlo)
    peak = _one_switch(dist, y0, yf, up, down, vhi, True)
    valley = _one_switch(dist, y0, yf, down, up, vlo, False)
    return peak if peak.time <= valley.time else valley


def _one_switch(dist: float, y0: float, yf: float, first: Rate, then: Rate, cap: float,
                rising: bool) -> Profile:
    """A peak (``rising``: ``first`` speeds up to a switching speed, ``then`` brakes to yf) or
    a valley (the mirror), with a cruise at the cap or where ``first`` stops pushing."""
    sign = 1.0 if rising else -1.0
    start = max(y0, yf) if rising else min(y0, yf)
    reach = first.reach(y0, rising)
    edge = min(cap, reach) if rising else max(cap, reach)
    if (edge - start) * sign < 0.0:
        edge = start

    def covered(v: float) -> tuple[float, float]:
        t1, d1 = first.between(y0, v)
        t2, d2 = then.between(v, yf)
        return t1 + t2, d1 + d2

    t0, d0 = covered(start)
    if not math.isfinite(t0) or (d0 - dist) * sign > 1e-9:
        return NONE  # even the shortest such profile goes past
    if math.isfinite(edge):
        te, de = covered(edge)
        if math.isfinite(te) and (dist - de) * sign >= 0.0:  # cruise at the edge
            cruise = (dist - de) / edge if edge else (0.0 if abs(dist - de) <= 1e-9 else -1.0)
            # a cruise needs the first level to push that way or hold the speed (a level
            # that brakes where the profile should speed up cannot cruise)
            held = first.at(y0) * sign > FLOOR or abs(first.at(y0)) <= FLOOR
            if cruise < 0.0 or (cruise > 1e-9 and not held):
                return NONE  # the cruise would have to go the other way, or cannot be
            rise = first.between(y0, edge)[0]
            holds = edge == reach  # the level itself keeps that speed
            return Profile(te + cruise, rising, rise + cruise if holds else rise)
    else:
        edge = start + sign * max(1.0, abs(start))
        while covered(edge)[1] * sign < dist * sign:
            edge = start + 2.0 * (edge - start)
            if abs(edge) > 1e9:
                return NONE
    lo, hi = start, edge
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        t, d = covered(mid)
        if not math.isfinite(t):
            hi = mid
            continue
        lo, hi = (mid, hi) if (d - dist) * sign < 0.0 else (lo, mid)
    t, _ = covered(hi)
    return Profile(t, rising, first.between(y0, hi)[0]) if math.isfinite(t) else NONE


def box_profile(x0: float, y0: float, box: tuple[float, float], band: tuple[float, float],
                up: Rate, down: Rate, cap: tuple[float, float] = (-math.inf, math.inf)
                ) -> Profile:
    """The least-time profile (:func:`profile`) from position ``x0`` and speed ``y0`` to a
    position in ``box`` with the speed in ``band`` (within ``cap``), over a few end points:
    the box's near and far ends arriving at the band's fastest speed that way, and the point
    where bringing the speed into the band straight away ends (if that is in the box)."""
    (lo, hi), (yl, yh) = box, band
    if lo > hi or yl > yh:
        return NONE
    if lo <= x0 <= hi and yl <= y0 <= yh:
        return Profile(0.0, True, 0.0)
    ends: list[tuple[float, float]] = []
    if x0 < hi:
        ends.extend((xf, yh) for xf in (lo, hi) if math.isfinite(xf) and xf > x0)
    if x0 > lo:
        ends.extend((xf, yl) for xf in (hi, lo) if math.isfinite(xf) and xf < x0)
    yf = min(max(y0, yl), yh)
    t, d = (down if y0 > yf else up).between(y0, yf)
    if math.isfinite(t) and lo <= x0 + d <= hi:
        ends.append((x0 + d, yf))
    best = NONE
    for xf, vf in ends:
        found = profile(xf - x0, y0, vf, up, down, cap[1], cap[0])
        if found.time < best.time:
            best = found
    return best


__all__ = ["CELLS", "FLOOR", "NONE", "Profile", "Rate", "box_profile", "point_time",
           "profile"]
