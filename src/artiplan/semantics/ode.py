"""Solving dx/dt = (sum of the active rates) from a state: exact polynomials, or RK4.

With polynomial rates and no changing fluent whose rate depends on itself (directly or through
others), integrating in dependency order gives every fluent as an exact polynomial in dt (the
Taylor series terminates). Otherwise :class:`Integrator` steps RK4 with a fixed step.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

from artiplan.pddl.task import BinOp, Const, FluentRef, Neg, NumExpr
from artiplan.semantics import polynomial as P
from artiplan.semantics.expressions import compile_expr


def expr_poly(expr: NumExpr, poly_of: Callable[[int], P.Poly | None]) -> P.Poly | None:
    if isinstance(expr, Const):
        return (float(expr.value),)
    if isinstance(expr, FluentRef):
        return poly_of(expr.index)
    if isinstance(expr, Neg):
        inner = expr_poly(expr.operand, poly_of)
        return None if inner is None else P.neg(inner)
    assert isinstance(expr, BinOp)
    a = expr_poly(expr.left, poly_of)
    b = expr_poly(expr.right, poly_of)
    if a is None or b is None:
        return None
    if expr.op == "+":
        return P.add(a, b)
    if expr.op == "-":
        return P.sub(a, b)
    if expr.op == "*":
        return P.mul(a, b)
    if len(b) == 1 and b[0] != 0.0:  # division by a constant only
        return P.scale(a, 1.0 / b[0])
    return None


def polynomial_solution(
    values: Sequence[float], rates: dict[int, list[NumExpr]]
) -> tuple[P.Poly, ...] | None:
    """Exact polynomial of every fluent, or None (a cycle or a non-polynomial rate)."""
    solved: dict[int, P.Poly] = {}
    visiting: set[int] = set()
    failed = False

    def poly_of(i: int) -> P.Poly | None:
        nonlocal failed
        if i in solved:
            return solved[i]
        if i not in rates:
            return (values[i],)
        if i in visiting or failed:  # x depends on itself: exponential, not polynomial
            failed = True
            return None
        visiting.add(i)
        total: P.Poly = (0.0,)
        for rate in rates[i]:
            rp = expr_poly(rate, poly_of)
            if rp is None:
                failed = True
                return None
            total = P.add(total, rp)
        visiting.discard(i)
        solved[i] = P.integrate(total, values[i])
        return solved[i]

    for i in rates:
        if poly_of(i) is None:
            return None
    return tuple(solved.get(i, (v,)) for i, v in enumerate(values))


class Integrator:
    """RK4 with a fixed step and checkpoints (the non-polynomial fallback)."""

    def __init__(self, values: Sequence[float], rates: dict[int, list[NumExpr]], step: float):
        self.step = step
        self.terms = [(i, [compile_expr(r) for r in rs]) for i, rs in rates.items()]
        self.checkpoints: list[tuple[float, ...]] = [tuple(values)]

    def _deriv(self, x: Sequence[float]) -> list[float]:
        d = [0.0] * len(x)
        for i, fns in self.terms:
            d[i] = sum(f(x) for f in fns)
        return d

    def _rk4(self, x: tuple[float, ...], h: float) -> tuple[float, ...]:
        k1 = self._deriv(x)
        k2 = self._deriv([a + 0.5 * h * b for a, b in zip(x, k1, strict=True)])
        k3 = self._deriv([a + 0.5 * h * b for a, b in zip(x, k2, strict=True)])
        k4 = self._deriv([a + h * b for a, b in zip(x, k3, strict=True)])
        return tuple(
            a + h / 6.0 * (b1 + 2 * b2 + 2 * b3 + b4)
            for a, b1, b2, b3, b4 in zip(x, k1, k2, k3, k4, strict=True)
        )

    def values_at(self, dt: float) -> tuple[float, ...]:
        k = int(dt / self.step)
        while len(self.checkpoints) <= k:
            self.checkpoints.append(self._rk4(self.checkpoints[-1], self.step))
        rest = dt - k * self.step
        base = self.checkpoints[k]
        return base if rest <= 0.0 else self._rk4(base, rest)
