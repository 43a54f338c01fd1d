"""Sets of reals as sorted unions of intervals, and 1-D travel along them.

The heuristic reads a goal on one fluent (``x > 150``, ``(or (> x 355) (< x 5))``) as the set of
values that satisfy it, and a wrap-around event (``x >= 360 -> x := x - 360``) as a trigger set and
a jump. Open and closed ends are not told apart: a relaxation needs distances, not boundaries.
"""

from __future__ import annotations

import math

from artiplan.pddl.task import And, Comparison, Condition, Not, Or, Truth
from artiplan.records import dataclass
from artiplan.semantics.walks import linear_difference

Intervals = tuple[tuple[float, float], ...]
EVERYTHING: Intervals = ((-math.inf, math.inf),)
NOTHING: Intervals = ()


def union(a: Intervals, b: Intervals) -> Intervals:
    merged: list[list[float]] = []
    for lo, hi in sorted(a + b):
        if merged and lo <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], hi)
        else:
            merged.append([lo, hi])
    return tuple((lo, hi) for lo, hi in merged)


def intersect(a: Intervals, b: Intervals) -> Intervals:
    out = []
    for lo1, hi1 in a:
        for lo2, hi2 in b:
            lo, hi = max(lo1, lo2), min(hi1, hi2)
            if lo <= hi:
                out.append((lo, hi))
    return union(tuple(out), ())


def complement(a: Intervals) -> Intervals:
    out = []
    prev = -math.inf
    for lo, hi in a:
        if lo > prev:
            out.append((prev, lo))
        prev = hi
    if prev < math.inf:
        out.append((prev, math.inf))
    return tuple(out)


def contains(a: Intervals, x: float) -> bool:
    return any(lo <= x <= hi for lo, hi in a)


def condition_set(cond: Condition, fluent: int) -> Intervals | None:
    """The values of ``fluent`` satisfying ``cond``, if ``cond`` reads only that fluent linearly."""
    if isinstance(cond, Truth):
        return EVERYTHING if cond.value else NOTHING
    if isinstance(cond, Not):
        inner = condition_set(cond.operand, fluent)
        return None if inner is None else complement(inner)
    if isinstance(cond, (And, Or)):
        acc = EVERYTHING if isinstance(cond, And) else NOTHING
        for part in cond.parts:
            s = condition_set(part, fluent)
            if s is None:
                return None
            acc = intersect(acc, s) if isinstance(cond, And) else union(acc, s)
        return acc
    if not isinstance(cond, Comparison):
        return None
    lin = linear_difference(cond)
    if lin is None or set(lin[0]) != {fluent}:
        return None
    a, b = lin[0][fluent], lin[1]
    root = -b / a
    positive = {">": True, ">=": True, "<": False, "<=": False}.get(cond.op)
    if positive is None:  # '='
        return ((root, root),)
    if a < 0:
        positive = not positive
    return ((root, math.inf),) if positive else ((-math.inf, root),)


@dataclass(frozen=True)
class Jump:
    """An event on one fluent: when the value enters ``trigger`` it becomes ``scale*x + shift``."""

    trigger: Intervals
    scale: float
    shift: float


def travel(x: float, direction: float, target: Intervals, jumps: tuple[Jump, ...]) -> float:
    """Distance moved (value units) from ``x`` in ``direction`` until inside ``target``.

    Jumps (wrap-around events) apply when their trigger set is reached; ``inf`` if never.
    """
    dist = 0.0
    for _ in range(6):
        if contains(target, x):
            return dist
        entry = _next_point(x, direction, target)
        trig, jump = _next_jump(x, direction, jumps)
        if abs(entry - x) <= trig or jump is None:
            return dist + abs(entry - x)
        y = x + direction * trig
        dist += trig
        x = jump.scale * y + jump.shift
    return math.inf


def _next_jump(x: float, direction: float, jumps: tuple[Jump, ...]) -> tuple[float, Jump | None]:
    """The distance to the first jump reached from ``x`` in ``direction``, and the jump (inf,
    None if none). A trigger only counts when moving into it (not when leaving its boundary)."""
    trig, jump = math.inf, None
    for j in jumps:
        p = _next_point(x + direction * 1e-9, direction, j.trigger)
        if abs(p - x) < trig:
            trig, jump = abs(p - x), j
    return trig, jump


def _next_point(x: float, direction: float, s: Intervals) -> float:
    """First point of ``s`` reached from ``x`` moving in ``direction`` (inf if none)."""
    best = math.inf if direction > 0 else -math.inf
    for lo, hi in s:
        if lo <= x <= hi:
            return x
        if direction > 0 and lo > x:
            best = min(best, lo)
        elif direction < 0 and hi < x:
            best = max(best, hi)
    return best


def displace(x: float, direction: float, dist: float, jumps: tuple[Jump, ...]) -> float:
    """Where ``x`` ends after moving ``dist`` (value units) in ``direction``, through jumps."""
    for _ in range(16):
        trig, jump = _next_jump(x, direction, jumps)
        if jump is None or trig > dist:
            return x + direction * dist
        dist -= trig
        y = x + direction * trig
        x = jump.scale * y + jump.shift
    return x
