"""Continuous change between happenings: flows, and the exact times conditions change truth value.

While the active processes stay the same, every fluent evolves by ``dx/dt = sum of the rates of
the active processes acting on x``. When every rate is a polynomial in the fluents and no changing
fluent's rate depends (directly or not) on itself, the solution is a polynomial in the elapsed
time ``dt``: constant rates give straight lines (NG, UCM), a rate that is itself a fluent growing
at a constant rate gives a parabola (UACM). :func:`make_flow` computes those polynomials exactly
(integrating in dependency order: the Taylor series that terminates).

Anything else (a rate that reads its own fluent, a division by a changing fluent) falls back to a
numeric flow, flagged ``Flow.exact = False``: classic RK4 with step ``FlowConfig.numeric_step``
(1e-3 s), and crossing times found by scanning on that step and refining sign changes with
bisection to ``FlowConfig.root_xtol`` (1e-9 s). The scan can miss a condition
that is true only between two scan points (a touch); that is documented, not hidden.

Boundary handling (:func:`crossing_time`): the truth of a condition "on (0, eps)" is its *right
limit*, computed exactly from the sign of the first non-vanishing Taylor coefficient of
``left - right`` (a value within ``zero_tol`` of 0 counts as 0). The crossing time is the
earliest ``r > 0`` at which the truth *at* ``r`` or the right limit *after* ``r`` differs from
the initial right limit: the infimum of the times the condition is different, so an event with
``(> x c)`` fires at the instant ``x`` reaches ``c`` (what VAL's slack on strict comparisons
does too) and ``(>= x c)`` at the same instant.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field

from artiplan.pddl.task import (
    And,
    Atom,
    Comparison,
    Condition,
    Const,
    FluentRef,
    GroundProcess,
    Not,
    NumExpr,
    Or,
    Task,
)
from artiplan.semantics import polynomial as P
from artiplan.semantics.cache import per_task
from artiplan.semantics.expressions import (
    EXACT,
    CondFn,
    ExprFn,
    Tolerances,
    compare,
    compile_condition,
    compile_near,
    condition_parts,
    evaluate,
    expr_fluents,
    holds,
)
from artiplan.semantics.ode import Integrator, expr_poly, polynomial_solution
from artiplan.semantics.state import State


@dataclass(frozen=True)
class FlowConfig:
    """Numeric settings of flows and crossing times.

    Attributes:
        zero_tol: |left - right| at or below this counts as exactly on the boundary (units of
            the compared values; absorbs rounding, e.g. 360 computed as 359.99999999999994).
        numeric_step: RK4 step [s] of the non-polynomial fallback, and its scan step.
        root_xtol: Time tolerance [s] of the bisection in the fallback.
        numeric_horizon: Longest scan [s] of the fallback when no horizon is given.
    """

    zero_tol: float = 1e-9
    numeric_step: float = 1e-3
    root_xtol: float = 1e-9
    numeric_horizon: float = 3600.0


DEFAULT_FLOW = FlowConfig()


@dataclass
class Flow:
    """How the fluents evolve from ``start`` while ``processes`` stay active.

    Attributes:
        start: The state at dt = 0.
        processes: The active processes.
        changing: Fluents with at least one continuous effect.
        exact: True when ``polys`` holds the exact polynomial of every fluent.
        polys: Per fluent, coefficients in dt (lowest first); ``None`` when not exact.
    """

    start: State
    processes: tuple[GroundProcess, ...]
    changing: frozenset[int]
    exact: bool
    polys: tuple[P.Poly, ...] | None
    config: FlowConfig = DEFAULT_FLOW
    _numeric: Integrator | None = field(default=None, repr=False)
    #: Per comparison (by identity): it, its difference polynomial and its positive roots.
    _memo: dict[int, tuple[Comparison, P.Poly | None, list[float] | None]] = field(
        default_factory=dict, repr=False
    )
    #: Roots of ``fluent - constant``, by (fluent, constant).
    _simple: dict[tuple[int, float], list[float]] = field(default_factory=dict, repr=False)

    def values_at(self, dt: float) -> tuple[float, ...]:
        """Every fluent's value at ``start.time + dt`` [s] (dt >= 0)."""
        if self.polys is not None:
            return tuple(p[0] if len(p) == 1 else P.value(p, dt) for p in self.polys)
        assert self._numeric is not None
        return self._numeric.values_at(dt)

    def state_at(self, dt: float) -> State:
        """The state at ``start.time + dt`` (same facts)."""
        return State(self.start.time + dt, self.start.facts, self.values_at(dt))

    def coefficients(self, fluent: int) -> P.Poly | None:
        """Polynomial of ``fluent`` in dt (lowest degree first); None for a numeric flow."""
        return None if self.polys is None else self.polys[fluent]

    def expr_poly(self, expr: NumExpr) -> P.Poly | None:
        """``expr`` along this flow as a polynomial in dt; None if not polynomial."""
        if self.polys is None:
            return None
        return expr_poly(expr, lambda i: self.polys[i])  # type: ignore[index]

    @property
    def is_static(self) -> bool:
        """True when nothing changes (no active continuous effect)."""
        return not self.changing


def active_processes(
    task: Task, state: State, tol: Tolerances = EXACT
) -> tuple[GroundProcess, ...]:
    """The processes whose precondition holds *at* ``state`` (point semantics)."""
    return tuple(p for p in task.processes if holds(p.precondition, state, tol))


def make_flow(
    task: Task,
    state: State,
    processes: Sequence[GroundProcess],
    config: FlowConfig = DEFAULT_FLOW,
) -> Flow:
    """The flow of ``state`` under ``processes`` (exact polynomials when possible)."""
    rates: dict[int, list[NumExpr]] = {}
    for proc in processes:
        for ce in proc.continuous:
            rates.setdefault(ce.fluent, []).append(ce.rate)
    changing = frozenset(rates)
    polys = polynomial_solution(state.values, rates)
    if polys is not None:
        return Flow(state, tuple(processes), changing, True, polys, config)
    integ = Integrator(state.values, rates, config.numeric_step)
    return Flow(state, tuple(processes), changing, False, None, config, integ)


def settled_flow(
    task: Task, state: State, config: FlowConfig = DEFAULT_FLOW, max_rounds: int = 8
) -> Flow:
    """The flow that starts at ``state``: processes active on (t, t + eps).

    Starts from the processes that hold at ``state`` (differences within ``zero_tol`` count as
    0) and replaces the set by those whose precondition's right limit holds under the resulting
    flow, until it no longer changes (a boundary such as ``angle = 180`` with an increasing
    angle is decided by the rate).
    """
    procs = per_task(task, ("processes", config.zero_tol), lambda: _compile_processes(task, config))
    facts, values = state.facts, state.values
    point = [fn(facts, values) for _, fn, _, _ in procs]
    active = tuple(p for (p, *_), ok in zip(procs, point, strict=True) if ok)
    flow = make_flow(task, state, active, config)
    # Only a process with a comparison on its boundary can differ from its point truth.
    edge = [k for k, (_, _, _, near) in enumerate(procs) if near(values)]
    if not edge:
        return flow
    for _ in range(max_rounds):
        truth = list(point)
        for k in edge:
            proc, _, reads, _ = procs[k]
            if reads & flow.changing:
                truth[k] = right_holds(proc.precondition, flow)
        nxt = tuple(p for (p, *_), ok in zip(procs, truth, strict=True) if ok)
        if nxt == active:
            return flow
        active = nxt
        flow = make_flow(task, state, active, config)
    return flow


def _compile_processes(
    task: Task, config: FlowConfig
) -> list[tuple[GroundProcess, CondFn, set[int], ExprFn]]:
    snap = Tolerances(strict_slack=-config.zero_tol, eps=config.zero_tol)
    return [
        (
            p,
            compile_condition(p.precondition, snap),
            condition_parts(p.precondition)[1],
            compile_near(p.precondition, config.zero_tol),
        )
        for p in task.processes
    ]


# ------------------------------------------------------------------------ truth along a flow


def _comparison_poly(comp: Comparison, flow: Flow) -> P.Poly | None:
    hit = flow._memo.get(id(comp))
    if hit is not None and hit[0] is comp:
        return hit[1]
    left = flow.expr_poly(comp.left)
    right = flow.expr_poly(comp.right)
    poly = None if left is None or right is None else P.sub(left, right)
    flow._memo[id(comp)] = (comp, poly, None)
    return poly


def _comparison_roots(comp: Comparison, flow: Flow) -> list[float]:
    """All positive roots of ``left - right`` along an exact flow (memoised per flow).

    The common ``fluent op constant`` shape is memoised by (fluent, constant), so the many
    processes that test the same angle against the same bound share one root computation.
    """
    left, right = comp.left, comp.right
    if isinstance(left, Const) and isinstance(right, FluentRef):
        left, right = right, left
    if isinstance(left, FluentRef) and isinstance(right, Const) and flow.polys is not None:
        key = (left.index, right.value)
        roots = flow._simple.get(key)
        if roots is None:
            p = flow.polys[left.index]
            diff = (p[0] - right.value, *p[1:])
            roots = P.positive_roots(diff, math.inf, flow.config.zero_tol)
            flow._simple[key] = roots
        return roots
    poly = _comparison_poly(comp, flow)
    cached = flow._memo[id(comp)][2]
    if cached is None:
        cached = [] if poly is None else P.positive_roots(poly, math.inf, flow.config.zero_tol)
        flow._memo[id(comp)] = (comp, poly, cached)
    return cached


def _diff_at(comp: Comparison, flow: Flow, dt: float) -> float:
    values = flow.values_at(dt)
    return evaluate(comp.left, values) - evaluate(comp.right, values)


def _comparison_sign_after(comp: Comparison, flow: Flow, dt: float) -> int:
    zt = flow.config.zero_tol
    values = flow.start.values if dt == 0.0 else flow.values_at(dt)
    d = evaluate(comp.left, values) - evaluate(comp.right, values)
    if abs(d) > zt:  # off the boundary: the sign now is the sign right after
        return 1 if d > 0 else -1
    poly = _comparison_poly(comp, flow)
    if poly is not None:
        return P.sign_after(P.shift(poly, dt) if dt else poly, zt)
    d0 = _diff_at(comp, flow, dt)
    if abs(d0) > zt:
        return 1 if d0 > 0 else -1
    d1 = _diff_at(comp, flow, dt + 10 * flow.config.root_xtol)
    return 0 if d1 == 0 else (1 if d1 > 0 else -1)


def _truth(cond: Condition, facts: frozenset[int], comp: Callable[[Comparison], bool]) -> bool:
    if isinstance(cond, Atom):
        return cond.fact in facts
    if isinstance(cond, Comparison):
        return comp(cond)
    if isinstance(cond, And):
        return all(_truth(p, facts, comp) for p in cond.parts)
    if isinstance(cond, Or):
        return any(_truth(p, facts, comp) for p in cond.parts)
    if isinstance(cond, Not):
        return not _truth(cond.operand, facts, comp)
    return cond.value


def right_holds(cond: Condition, flow: Flow, dt: float = 0.0) -> bool:
    """Truth of ``cond`` on (dt, dt + eps) along ``flow`` (exact for polynomial flows)."""
    sign_op = {1: 1.0, 0: 0.0, -1: -1.0}
    return _truth(
        cond,
        flow.start.facts,
        lambda c: compare(c.op, sign_op[_comparison_sign_after(c, flow, dt)]),
    )


def point_holds(cond: Condition, flow: Flow, dt: float, tol: Tolerances = EXACT) -> bool:
    """Truth of ``cond`` at ``dt`` along ``flow``; differences within ``zero_tol`` count as 0."""
    values = flow.values_at(dt)
    zt = flow.config.zero_tol

    def comp(c: Comparison) -> bool:
        d = evaluate(c.left, values) - evaluate(c.right, values)
        return compare(c.op, 0.0 if abs(d) <= zt else d, tol)

    return _truth(cond, flow.start.facts, comp)


def crossing_time(
    cond: Condition, flow: Flow, horizon: float = math.inf, tol: Tolerances = EXACT
) -> float | None:
    """Earliest dt in (0, horizon] at which ``cond`` changes truth value along ``flow``.

    "Changes" (module docstring): its truth at dt, or right after dt, differs from its truth
    right after 0. None when it does not change within the horizon. ``tol`` reads the point
    truth (e.g. VAL's slack); the right limits are exact.
    """
    comps = _dynamic_comparisons(cond, flow.changing)
    if not comps:
        return None
    candidates = _candidate_times(comps, flow, horizon)
    first = next(candidates, None)
    if first is None:
        return None
    initial = right_holds(cond, flow, 0.0)
    for r in itertools.chain((first,), candidates):
        if point_holds(cond, flow, r, tol) != initial or right_holds(cond, flow, r) != initial:
            return r
    return None


def _bisect(comp: Comparison, flow: Flow, lo: float, hi: float, f_lo: float, xtol: float) -> float:
    """A sign change of ``left - right`` in [lo, hi] to within ``xtol`` [s] (the upper end of
    the final bracket: the first time the sign has changed)."""
    while hi - lo > xtol:
        mid = 0.5 * (lo + hi)
        f_mid = _diff_at(comp, flow, mid)
        if f_mid == 0.0:
            return mid
        if (f_mid > 0) == (f_lo > 0):
            lo, f_lo = mid, f_mid
        else:
            hi = mid
    return hi


# Memo: condition id -> (the condition, its comparisons with the fluents each reads). The
# condition is kept in the entry, so its id cannot be reused while the entry lives.
_COMPARISONS: dict[int, tuple[Condition, list[tuple[Comparison, set[int]]]]] = {}


def _dynamic_comparisons(cond: Condition, changing: frozenset[int]) -> list[Comparison]:
    hit = _COMPARISONS.get(id(cond))
    if hit is None or hit[0] is not cond:
        if len(_COMPARISONS) > 100_000:
            _COMPARISONS.clear()
        comps = condition_parts(cond)[2]
        hit = (cond, [(c, expr_fluents(c.left) | expr_fluents(c.right)) for c in comps])
        _COMPARISONS[id(cond)] = hit
    return [c for c, reads in hit[1] if reads & changing]


def _candidate_times(comps: list[Comparison], flow: Flow, horizon: float) -> Iterator[float]:
    """Every dt in (0, horizon] where some comparison's difference is 0, ascending."""
    times: set[float] = set()
    if flow.exact:
        for c in comps:
            times.update(r for r in _comparison_roots(c, flow) if r <= horizon)
        yield from sorted(times)
    else:
        yield from _numeric_candidates(comps, flow, horizon)


def _numeric_candidates(comps: list[Comparison], flow: Flow, horizon: float) -> Iterator[float]:
    """Sign changes on a scan of step ``numeric_step``, refined by bisection (fallback)."""
    cfg = flow.config
    end = min(horizon, cfg.numeric_horizon)
    n = max(1, math.ceil(end / cfg.numeric_step))
    prev = [_diff_at(c, flow, 0.0) for c in comps]
    for k in range(1, n + 1):
        found: list[float] = []
        t1 = min(end, k * cfg.numeric_step)
        t0 = (k - 1) * cfg.numeric_step
        cur = [_diff_at(c, flow, t1) for c in comps]
        for c, a, b in zip(comps, prev, cur, strict=True):
            if b == 0.0 or (abs(a) > cfg.zero_tol and a * b < 0):
                if b == 0.0:
                    found.append(t1)
                else:
                    found.append(_bisect(c, flow, t0, t1, a, cfg.root_xtol))
        yield from sorted(found)
        prev = cur
