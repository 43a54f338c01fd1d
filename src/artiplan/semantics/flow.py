"""Continuous change between happenings: exact polynomial flows, and one numeric fallback.

While the active processes stay the same, ``dv/dt`` is the sum of their rates. Three cases:

* rates linear in the fluents, ``dv/dt = A v + b``, with ``A`` nilpotent (no fluent's rate
  depends on itself through a chain; NG and UCM give degree 1, UACM degree 2): the Taylor series
  terminates, ``v(dt) = v + sum_k D_k dt^k / k!`` with ``D_1 = A v + b``, ``D_{k+1} = A D_k``;
* rates polynomial in the fluents, acyclic: each fluent integrated as a polynomial in
  dependency order;
* anything else (a rate that reads its own fluent, a quotient or a fractional power of a
  changing value): :class:`NumericFlow`, RK4 with step-doubling error control, and crossings
  bracketed by interval enclosures of every watched comparison over every step, so no crossing
  can hide between two steps (a *touch* is resolved to ``tol.root`` seconds). Its estimated
  error is reported (``error``).

Exact flows hold, per moving fluent, the coefficients ``(c1, c2, ...)`` of
``v(dt) = v + c1 dt + c2 dt^2 + ...``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

from artiplan.pddl.task import BinOp, Const, FluentRef, NumExpr
from artiplan.records import dataclass
from artiplan.semantics import polynomial as P
from artiplan.semantics.compiled import Comparison, Process
from artiplan.semantics.walks import (
    Box,
    DomainError,
    evaluate,
    expr_source,
    interval,
    source_function,
    to_poly,
)
from artiplan.tolerances import Tolerances

Values = tuple[float, ...]
#: Taylor terms tried before a linear flow counts as not polynomial.
MAX_DEGREE = 6
#: Roots at or below this elapsed time [s] are "now", not a future change.
DT_MIN = 1e-10


class Flow:
    """The flow of the active processes: exact (:attr:`coeffs`) or numeric (a subclass)."""

    __slots__ = ("coeffs", "exact", "degree", "changing")

    def __init__(self, coeffs: dict[int, tuple[float, ...]], changing: frozenset[int]) -> None:
        self.coeffs = coeffs
        self.exact = True
        self.degree = max((len(c) for c in coeffs.values()), default=0)
        self.changing = changing

    @property
    def moving(self) -> bool:
        """True when some fluent changes."""
        return bool(self.changing)

    def values(self, start: Values, dt: float) -> Values:
        """Every fluent ``dt`` [s] after ``start``."""
        if not self.coeffs or dt == 0.0:
            return start
        out = list(start)
        for f, cs in self.coeffs.items():
            acc = 0.0
            for c in reversed(cs):
                acc = acc * dt + c
            out[f] = start[f] + acc * dt
        return tuple(out)

    def poly(self, comp: Comparison, start: Values) -> P.Poly | None:
        """``p(dt)`` of comparison ``p op 0`` along the flow, lowest degree first."""
        if comp.linear is not None:
            coeffs, const = comp.linear
            c0, higher = const, [0.0] * self.degree
            for j, a in coeffs.items():
                c0 += a * start[j]
                for k, c in enumerate(self.coeffs.get(j, ())):
                    higher[k] += a * c
            while higher and higher[-1] == 0.0:
                higher.pop()
            return (c0, *higher)
        return to_poly(comp.expr, lambda i: (start[i], *self.coeffs.get(i, ())))

STILL = Flow({}, frozenset())


@dataclass(frozen=True)
class Shape:
    """What the active processes add up to, independent of the values: ``dv/dt = A v + b``
    plus the rates that are not linear (``raw``)."""

    b: dict[int, float]
    a_rows: dict[int, dict[int, float]]
    raw: tuple[tuple[int, NumExpr], ...]

    @property
    def changing(self) -> frozenset[int]:
        return frozenset(self.b)


def shape_of(processes: Sequence[Process], active: tuple[int, ...]) -> Shape:
    b: dict[int, float] = {}
    a_rows: dict[int, dict[int, float]] = {}
    raw: list[tuple[int, NumExpr]] = []
    for pi in active:
        for fluent, expr, lin in processes[pi].rates:
            b.setdefault(fluent, 0.0)
            if lin is None:
                raw.append((fluent, expr))
                continue
            coeffs, const = lin
            b[fluent] += const
            if coeffs:
                row = a_rows.setdefault(fluent, {})
                for j, a in coeffs.items():
                    row[j] = row.get(j, 0.0) + a
    return Shape(b, a_rows, tuple(raw))


def make_flow(shape: Shape, values: Values, tol: Tolerances) -> Flow:
    """The flow of ``shape`` from ``values``: exact when possible, else numeric."""
    if not shape.b:
        return STILL
    if not shape.raw:
        coeffs = _linear_taylor(shape, values)
        if coeffs is not None:
            return Flow(coeffs, shape.changing)
    coeffs = _polynomial(shape, values)
    if coeffs is not None:
        return Flow(coeffs, shape.changing)
    return NumericFlow(shape, values, tol)


def _linear_taylor(shape: Shape, values: Values) -> dict[int, tuple[float, ...]] | None:
    """The terminating Taylor series of ``dv/dt = A v + b`` (None if ``A`` is not nilpotent)."""
    fl = sorted(shape.b)
    if not shape.a_rows:
        return {f: (shape.b[f],) for f in fl if shape.b[f] != 0.0}
    rows = shape.a_rows
    first = {f: shape.b[f] + sum(a * values[j] for j, a in rows.get(f, {}).items()) for f in fl}
    own = {f: [(j, a) for j, a in row.items() if j in shape.b] for f, row in rows.items()}
    derivs = [first]
    while any(derivs[-1].values()):
        if len(derivs) >= MAX_DEGREE:
            return None
        prev = derivs[-1]
        derivs.append({f: sum(a * prev[j] for j, a in own.get(f, ())) for f in fl})
    if len(derivs) > 1:
        derivs.pop()
    out = {}
    for f in fl:
        cs = [d[f] / math.factorial(k + 1) for k, d in enumerate(derivs)]
        while cs and cs[-1] == 0.0:
            cs.pop()
        if cs:
            out[f] = tuple(cs)
    return out


def _polynomial(shape: Shape, values: Values) -> dict[int, tuple[float, ...]] | None:
    """Every changing fluent as a polynomial, integrating in dependency order (None for a
    cycle or a rate that is not polynomial)."""
    rates: dict[int, list[NumExpr]] = {}
    for f, e in shape.raw:
        rates.setdefault(f, []).append(e)
    for f, row in shape.a_rows.items():
        for j, a in row.items():
            rates.setdefault(f, []).append(BinOp("*", Const(a), FluentRef(j)))
    for f, c in shape.b.items():
        if c != 0.0:
            rates.setdefault(f, []).append(Const(c))
    solved: dict[int, P.Poly] = {}
    visiting: set[int] = set()

    def poly_of(i: int) -> P.Poly | None:
        if i in solved:
            return solved[i]
        if i not in rates:
            return (values[i],)
        if i in visiting:
            return None
        visiting.add(i)
        total: P.Poly = (0.0,)
        for rate in rates[i]:
            rp = to_poly(rate, poly_of)
            if rp is None:
                return None
            total = P.add(total, rp)
        visiting.discard(i)
        solved[i] = P.integrate(total, values[i])
        return solved[i]

    out = {}
    for f in shape.b:
        p = poly_of(f)
        if p is None:
            return None
        if len(p) > 1:
            out[f] = tuple(p[1:])
    return out


class NumericFlow(Flow):
    """RK4 with step-doubling error control from fixed start values; crossings bracketed by
    interval enclosures (module docstring). ``error``: the largest step-doubling estimate of
    the local error so far (units of the values)."""

    __slots__ = ("start", "tol", "_shape", "_deriv", "_times", "_states", "error", "_boxes")

    #: Local error allowed per step, relative to max(1, |value|).
    RTOL = 1e-9
    H_MAX = 2.0
    H_MIN = 1e-6
    #: How far [s] and how many steps a search for a crossing looks ahead at most.
    HORIZON = 3600.0
    MAX_STEPS = 100_000

    def __init__(self, shape: Shape, start: Values, tol: Tolerances) -> None:
        super().__init__({}, shape.changing)
        self.exact = False
        self.start, self.tol = start, tol
        terms: dict[int, list[str]] = {}
        for f, c in shape.b.items():
            terms.setdefault(f, []).append(repr(c))
        for f, row in shape.a_rows.items():
            terms[f] += [f"{a!r} * V[{j}]" for j, a in row.items()]
        for f, e in shape.raw:
            terms[f].append(expr_source(e))
        body = ", ".join(f"({f}, {' + '.join(t)})" for f, t in sorted(terms.items()))
        self._deriv: Callable[[Sequence[float]], list[tuple[int, float]]] = source_function(
            f"lambda V: [{body}]")
        self._shape = shape
        self._times: list[float] = [0.0]
        self._states: list[Values] = [start]
        self._boxes: list[dict[int, Box]] = []
        self.error = 0.0

    # -------------------------------------------------------------------------- integration
    def _rk4(self, x: Values, h: float) -> Values:
        def add(base: Values, k: list[tuple[int, float]], s: float) -> Values:
            out = list(base)
            for f, d in k:
                out[f] = base[f] + s * d
            return tuple(out)

        k1 = self._deriv(x)
        k2 = self._deriv(add(x, k1, 0.5 * h))
        k3 = self._deriv(add(x, k2, 0.5 * h))
        k4 = self._deriv(add(x, k3, h))
        out = list(x)
        for (f, a), (_, b), (_, c), (_, d) in zip(k1, k2, k3, k4, strict=True):
            out[f] = x[f] + h / 6.0 * (a + 2.0 * b + 2.0 * c + d)
        return tuple(out)

    def _step(self) -> None:
        """Extend the checkpoints by one accepted step (and its enclosure)."""
        x, t = self._states[-1], self._times[-1]
        h = min(self.H_MAX, max(self.H_MIN, (t - self._times[-2]) * 2.0 if len(self._times) > 1
                                else 1e-3))
        while True:
            try:
                full = self._rk4(x, h)
                half = self._rk4(self._rk4(x, 0.5 * h), 0.5 * h)
            except DomainError:  # a stage left the rate's domain (sqrt of a level below 0)
                if h <= self.H_MIN:
                    raise
                h *= 0.5
                continue
            except OverflowError:  # the solution blows up (v' = -c v^2 below 0): inf from here
                self._times.append(t + h)
                self._states.append(tuple(math.inf if f in self.changing else v
                                          for f, v in enumerate(x)))
                self._boxes.append({f: (-math.inf, math.inf) for f in self.changing})
                return
            err = max((abs(full[f] - half[f]) / max(1.0, abs(half[f])) for f in self.changing),
                      default=0.0)
            if err <= self.RTOL or h <= self.H_MIN:
                break
            h *= 0.5
        box = self._enclose(x, half, h)
        self.error = max(self.error, err)
        self._times.append(t + h)
        self._states.append(half)
        self._boxes.append(box)

    def _enclose(self, x: Values, y: Values, h: float) -> dict[int, Box]:
        """Boxes holding every changing fluent over a step of ``h`` [s] from ``x`` (to ``y``):
        the endpoints' hull inflated until ``x + [0, h] F(box)`` stays inside it."""
        box = {f: (min(x[f], y[f]), max(x[f], y[f])) for f in self.changing}
        for _ in range(12):
            at = _within(box, x)
            grown: dict[int, Box] = {}
            ok = True
            for f in self.changing:
                lo, hi = _rate_interval(self._shape, f, at)
                cand = (x[f] + min(0.0, h * lo), x[f] + max(0.0, h * hi))
                if cand[0] < box[f][0] or cand[1] > box[f][1]:
                    ok = False
                width = max(cand[1] - cand[0], 1e-12)
                grown[f] = (min(box[f][0], cand[0]) - 0.1 * width,
                            max(box[f][1], cand[1]) + 0.1 * width)
            if ok:
                return box
            box = grown
        return {f: (-math.inf, math.inf) for f in self.changing}

    def _reach(self, dt: float) -> int:
        """Index of the last checkpoint at or before ``dt`` (stepping on as needed)."""
        while self._times[-1] < dt:
            self._step()
        lo, hi = 0, len(self._times) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if self._times[mid] <= dt:
                lo = mid
            else:
                hi = mid - 1
        return lo

    def values(self, start: Values, dt: float) -> Values:
        del start  # bound to its own start values
        if dt <= 0.0:
            return self.start
        k = self._reach(dt)
        rest = dt - self._times[k]
        base = self._states[k]
        return base if rest <= 0.0 else self._rk4(base, rest)

    # ---------------------------------------------------------------------------- crossings
    def crossing(self, comps: Sequence[Comparison], horizon: float) -> float | None:
        """The earliest dt in (0, horizon] [s] at which one of ``comps`` may change sign
        (bracketed: a step whose enclosure of ``p`` excludes 0 cannot hold a crossing)."""
        if not comps:
            return None
        end = min(horizon, self.HORIZON)
        k = 0
        while self._times[k] < end and k < self.MAX_STEPS:
            if k + 1 >= len(self._times):
                self._step()
                if not all(math.isfinite(v) and abs(v) < 1e300 for v in self._states[-1]):
                    return None  # the solution blows up: nothing is watched beyond
            t0, t1 = self._times[k], min(self._times[k + 1], end)
            box = self._boxes[k]
            x0 = self._states[k]
            for comp in comps:
                lo, hi = interval(comp.expr, _within(box, x0))
                if lo > 0.0 or hi < 0.0:
                    continue
                found = self._bisect(comp, max(t0, DT_MIN), t1)
                if found is not None:
                    return found
            k += 1
        return None

    def _bisect(self, comp: Comparison, t0: float, t1: float) -> float | None:
        """First sign change (or touch of 0) of ``p`` in [t0, t1] [s], to ``tol.root``: halve
        the interval while an enclosure of ``p`` over a half can reach 0."""
        def p_of(x: Values) -> float:
            return evaluate(comp.expr, x)

        x0, x1 = self.values(self.start, t0), self.values(self.start, t1)
        a, b = p_of(x0), p_of(x1)
        if abs(a) <= self.tol.zero and t0 > DT_MIN:
            return t0
        if a * b < 0.0 or b == 0.0:
            lo, hi = t0, t1
            while hi - lo > self.tol.root:
                mid = 0.5 * (lo + hi)
                m = p_of(self.values(self.start, mid))
                if m != 0.0 and (m > 0.0) == (a > 0.0):
                    lo = mid
                else:
                    hi = mid
            return hi
        if t1 - t0 <= 1e-7:  # a touch: at the bracket's resolution, is p (nearly) 0?
            mid = 0.5 * (t0 + t1)
            return mid if abs(p_of(self.values(self.start, mid))) <= self.tol.zero else None
        mid = 0.5 * (t0 + t1)
        for lo, hi in ((t0, mid), (mid, t1)):
            xa, xb = self.values(self.start, lo), self.values(self.start, hi)
            box = self._enclose(xa, xb, hi - lo)
            e_lo, e_hi = interval(comp.expr, _within(box, xa))
            if e_lo > 0.0 or e_hi < 0.0:
                continue  # no zero in this half
            found = self._bisect(comp, lo, hi)
            if found is not None:
                return found
        return None

    def sign_after(self, comp: Comparison, dt: float) -> int:
        """Sign of ``p`` just after ``dt`` (0 if it stays within ``tol.zero``)."""
        step = max(1e-7, 10 * self.tol.root)
        for probe in (dt, dt + step):
            v = evaluate(comp.expr, self.values(self.start, probe))
            if abs(v) > self.tol.zero:
                return 1 if v > 0 else -1
        return 0


def _within(box: dict[int, Box], x: Values) -> Callable[[int], Box]:
    """Fluent -> its box (the changing ones) or its value (the others)."""
    return lambda i: box.get(i, (x[i], x[i]))


def _rate_interval(shape: Shape, f: int, box: Callable[[int], Box]) -> Box:
    """Enclosure of fluent ``f``'s total rate over ``box``."""
    lo = hi = shape.b.get(f, 0.0)
    for j, a in shape.a_rows.get(f, {}).items():
        bl, bh = box(j)
        lo, hi = lo + min(a * bl, a * bh), hi + max(a * bl, a * bh)
    for g, e in shape.raw:
        if g == f:
            el, eh = interval(e, box)
            lo, hi = lo + el, hi + eh
    return lo, hi
