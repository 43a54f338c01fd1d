"""Exact continuous change between happenings: fluents as polynomials of the elapsed time.

While the set of active processes does not change, ``dv/dt = A v + b`` (rates linear in the
fluents, the case of every NG/UCM/UACM model). When ``A`` is nilpotent (no fluent's rate depends,
through a chain, on itself) the solution is a polynomial: ``v(dt) = sum_k D_k dt^k / k!`` with
``D_1 = A v + b`` and ``D_{k+1} = A D_k``. NG and UCM give degree 1, UACM degree 2. Roots of degree
<= 2 are solved in closed form, higher degrees with ``numpy.roots``.

Fallback (documented, counted in the statistics as ``fallback_steps``): rates that are not linear
in the fluents, or a non-nilpotent ``A``, are frozen at their current value for at most
``fallback_step`` seconds (explicit Euler), and the waits re-plan from there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from artiplan.pddl.task import BinOp, Const, FluentRef, Neg, NumExpr
from artiplan.search.compiled import CompiledComparison, CompiledProcess

MAX_DEGREE = 4
#: roots at or below this elapsed time [s] count as "now", not as a future change
DT_MIN = 1e-10

Poly = tuple[float, ...]  # c0 + c1 dt + c2 dt^2 ...


class Flow:
    """Per moving fluent its derivative coefficients ``(c1, c2, ...)``.

    ``v_f(dt) = v_f + c1 dt + c2 dt^2 + ...`` for ``dt <= valid_for`` [s].
    """

    __slots__ = ("coeffs", "valid_for", "exact", "degree", "_dense")

    def __init__(
        self, coeffs: dict[int, Poly], valid_for: float = math.inf, exact: bool = True
    ) -> None:
        self.coeffs = coeffs
        self.valid_for = valid_for
        self.exact = exact
        self.degree = max((len(c) for c in coeffs.values()), default=0)
        self._dense: np.ndarray | None = None

    @property
    def moving(self) -> bool:
        return bool(self.coeffs)

    def dense(self, n: int) -> np.ndarray:
        """Coefficients as an array ``(degree, n)``: row k holds every fluent's ``c_{k+1}``."""
        if self._dense is None:
            arr = np.zeros((max(self.degree, 1), n))
            for f, cs in self.coeffs.items():
                arr[: len(cs), f] = cs
            self._dense = arr
        return self._dense


STILL = Flow({})


@dataclass(frozen=True)
class FlowShape:
    """What the active processes add up to, independent of the values: ``dv/dt = A v + b``."""

    b: dict[int, float]
    a_rows: dict[int, dict[int, float]]
    raw: tuple[tuple[int, NumExpr], ...]  # rates that are not linear: frozen at their value

    def dense(self, n: int) -> tuple[list[int], np.ndarray, np.ndarray, np.ndarray]:
        """(fluents with a rate, b, A over all n fluents, A restricted to those fluents)."""
        cached = _DENSE.get(id(self))
        if cached is not None and cached[0] is self:
            return cached[1]
        fl = sorted(self.b)
        pos = {f: i for i, f in enumerate(fl)}
        bvec = np.array([self.b[f] for f in fl])
        a_full = np.zeros((len(fl), n))
        a_own = np.zeros((len(fl), len(fl)))
        for f, row in self.a_rows.items():
            for j, a in row.items():
                a_full[pos[f], j] += a
                if j in pos:
                    a_own[pos[f], pos[j]] += a
        out = (fl, bvec, a_full, a_own)
        _DENSE[id(self)] = (self, out)
        return out


_DENSE: dict[int, tuple[FlowShape, tuple[list[int], np.ndarray, np.ndarray, np.ndarray]]] = {}


def flow_shape(processes: list[CompiledProcess], active: tuple[int, ...]) -> FlowShape:
    b: dict[int, float] = {}
    a_rows: dict[int, dict[int, float]] = {}
    raw: list[tuple[int, NumExpr]] = []
    for pi in active:
        for fluent, lin, expr in processes[pi].rates:
            if lin is None:
                raw.append((fluent, expr))
                b.setdefault(fluent, 0.0)
                continue
            coeffs, const = lin
            b[fluent] = b.get(fluent, 0.0) + const
            if coeffs:
                row = a_rows.setdefault(fluent, {})
                for j, a in coeffs.items():
                    row[j] = row.get(j, 0.0) + a
    return FlowShape(b, a_rows, tuple(raw))


def compute_flow(
    processes: list[CompiledProcess], active: tuple[int, ...], values: tuple[float, ...],
    fallback_step: float, shape: FlowShape | None = None,
) -> Flow:
    """The flow of the fluents while exactly the processes ``active`` run."""
    if not active:
        return STILL
    if shape is None:
        shape = flow_shape(processes, active)
    if shape.a_rows and not shape.raw:
        return _polynomial_flow(shape, values, fallback_step)
    b, a_rows = shape.b, shape.a_rows
    exact = not shape.raw
    first = dict(b)
    for fluent, expr in shape.raw:
        first[fluent] += _eval(expr, values)
    for f, row in a_rows.items():
        first[f] += sum(a * values[j] for j, a in row.items())
    derivs = [first]
    if a_rows:
        while any(derivs[-1].values()):
            if len(derivs) >= MAX_DEGREE:
                exact = False
                break
            prev = derivs[-1]
            derivs.append(
                {f: sum(a * prev.get(j, 0.0) for j, a in row.items()) for f, row in a_rows.items()}
            )
    coeffs_out: dict[int, Poly] = {}
    if len(derivs) == 1:
        coeffs_out = {f: (c,) for f, c in first.items() if c != 0.0}
    else:
        for f in b:
            cs = [derivs[k].get(f, 0.0) / math.factorial(k + 1) for k in range(len(derivs))]
            while cs and cs[-1] == 0.0:
                cs.pop()
            if cs:
                coeffs_out[f] = tuple(cs)
    return Flow(coeffs_out, math.inf if exact else fallback_step, exact)


def _polynomial_flow(shape: FlowShape, values: tuple[float, ...], fallback_step: float) -> Flow:
    """``compute_flow`` for ``dv/dt = A v + b`` with numpy (UACM: speeds feed angles)."""
    fl, bvec, a_full, a_own = shape.dense(len(values))
    derivs = [bvec + a_full @ np.asarray(values)]
    exact = True
    while np.any(derivs[-1]):
        if len(derivs) >= MAX_DEGREE:
            exact = False
            break
        derivs.append(a_own @ derivs[-1])
    if not np.any(derivs[-1]) and len(derivs) > 1:
        derivs.pop()
    table = np.array(derivs) / np.array(
        [math.factorial(k + 1) for k in range(len(derivs))])[:, None]
    coeffs: dict[int, Poly] = {}
    for i, f in enumerate(fl):
        cs = [float(c) for c in table[:, i]]
        while cs and cs[-1] == 0.0:
            cs.pop()
        if cs:
            coeffs[f] = tuple(cs)
    return Flow(coeffs, math.inf if exact else fallback_step, exact)


def _eval(expr: NumExpr, values: tuple[float, ...]) -> float:
    if isinstance(expr, Const):
        return float(expr.value)
    if isinstance(expr, FluentRef):
        return values[expr.index]
    if isinstance(expr, Neg):
        return -_eval(expr.operand, values)
    left, right = _eval(expr.left, values), _eval(expr.right, values)
    if expr.op == "+":
        return left + right
    if expr.op == "-":
        return left - right
    if expr.op == "*":
        return left * right
    return left / right


def advance_values(values: tuple[float, ...], flow: Flow, dt: float) -> tuple[float, ...]:
    """Values after ``dt`` seconds of ``flow``."""
    if not flow.coeffs or dt == 0.0:
        return values
    out = list(values)
    for f, cs in flow.coeffs.items():
        acc = 0.0
        for c in reversed(cs):
            acc = acc * dt + c
        out[f] = values[f] + acc * dt
    return tuple(out)


# ------------------------------------------------------------------------ comparison polynomials


def _padd(p: Poly, q: Poly, sign: float = 1.0) -> Poly:
    n = max(len(p), len(q))
    return tuple(
        (p[i] if i < len(p) else 0.0) + sign * (q[i] if i < len(q) else 0.0) for i in range(n)
    )


def _pmul(p: Poly, q: Poly) -> Poly:
    out = [0.0] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, c in enumerate(q):
            out[i + j] += a * c
    return tuple(out)


def expr_poly(expr: NumExpr, values: tuple[float, ...], flow: Flow) -> Poly | None:
    """``expr`` along the flow as a polynomial of dt; ``None`` if it is not one."""
    if isinstance(expr, Const):
        return (float(expr.value),)
    if isinstance(expr, FluentRef):
        return (values[expr.index], *flow.coeffs.get(expr.index, ()))
    if isinstance(expr, Neg):
        inner = expr_poly(expr.operand, values, flow)
        return None if inner is None else tuple(-c for c in inner)
    assert isinstance(expr, BinOp)
    left, right = expr_poly(expr.left, values, flow), expr_poly(expr.right, values, flow)
    if left is None or right is None:
        return None
    if expr.op == "+":
        return _padd(left, right)
    if expr.op == "-":
        return _padd(left, right, -1.0)
    if expr.op == "*":
        return _pmul(left, right)
    if all(c == 0.0 for c in right[1:]) and right[0] != 0.0:
        return tuple(c / right[0] for c in left)
    return None


def comparison_poly(comp: CompiledComparison, values: tuple[float, ...], flow: Flow) -> Poly | None:
    """``p(dt)`` of comparison ``p op 0`` along the flow (``None``: not a polynomial)."""
    if comp.linear is not None:
        coeffs, const = comp.linear
        c0 = const
        degree = 0
        for j, a in coeffs.items():
            c0 += a * values[j]
            degree = max(degree, len(flow.coeffs.get(j, ())))
        if degree == 0:
            return (c0,)
        higher = [0.0] * degree
        for j, a in coeffs.items():
            for k, c in enumerate(flow.coeffs.get(j, ())):
                higher[k] += a * c
        return (c0, *higher)
    return expr_poly(comp.expr, values, flow)


def first_root(poly: Poly, horizon: float = math.inf) -> float | None:
    """Smallest root ``dt`` of ``poly`` with ``DT_MIN < dt <= horizon``, or ``None``."""
    cs = list(poly)
    while len(cs) > 1 and cs[-1] == 0.0:
        cs.pop()
    if len(cs) <= 1:
        return None
    if len(cs) == 2:
        root = -cs[0] / cs[1]
        return root if DT_MIN < root <= horizon else None
    if len(cs) == 3:
        roots = _quadratic_roots(cs[2], cs[1], cs[0])
    else:
        roots = [r.real for r in np.roots(cs[::-1]) if abs(r.imag) < 1e-9]
    found = [r for r in roots if DT_MIN < r <= horizon]
    return min(found) if found else None


def _quadratic_roots(a: float, b: float, c: float) -> list[float]:
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        # a double root lost to rounding still touches zero: keep the vertex when it is that close
        return [-b / (2.0 * a)] if disc > -1e-12 * max(1.0, b * b) else []
    sq = math.sqrt(disc)
    q = -0.5 * (b + math.copysign(sq, b))  # the numerically stable form
    roots = [q / a]
    if q != 0.0:
        roots.append(c / q)
    return roots
