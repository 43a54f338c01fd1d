"""Timing repair: the happening times of a plan skeleton, solved for, not searched on a grid.

A search on a grid of times (free waits of ``delta`` seconds) finds the right actions in the
right order long before it finds the right times: a car that must stop inside a 0.2 m window
at 36 m/s needs its braking time to the millisecond. Given the skeleton (the actions of a
search path, in order, with their grid times, and the action that should end it), this module
moves the times to satisfy every precondition, the goal, and the planner's distance from
events, with the kernel's exact trajectory as the model:

    margins(times) = [robustness(c) for each condition c read]

kept >= 2 * margin over the gaps between happenings by sequential quadratic programming of
our own (SLSQP's scheme with a zero objective: forward-difference Jacobians, a damped BFGS
curvature estimate, an L1 merit; scipy's SLSQP did this before and cost ~0.55 s of import),
stopping at the first point where every margin is >= 1.5 * margin; actions that the skeleton
applies one ``epsilon`` apart stay ``epsilon`` apart. The caller validates the result like any
plan (the kernel, not the optimiser, is the judge).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Condition
from artiplan.records import dataclass
from artiplan.semantics.compiled import CompiledTask
from artiplan.semantics.kernel import EventLog, Kernel
from artiplan.semantics.walks import conjuncts, robustness

#: Residual of a fact that does not hold, or of a run the kernel refuses (an event loop).
FAILED = 1e3


@dataclass(frozen=True)
class Repair:
    """Settings of a repair.

    Attributes:
        margin: Every comparison must hold by this much (its units) [-].
        epsilon: Separation [s] of actions applied one after the other.
        event_gap: No action closer than this [s] to an event.
        max_evals: Budget of trajectory simulations for the optimiser.
        grid: Times are rounded to this [s] (the plan file's decimals).
    """

    margin: float = 1e-4
    epsilon: float = 0.001
    event_gap: float = 0.015
    max_evals: int = 300
    grid: float = 1e-6


class TimingProblem:
    """The margins of a skeleton as a function of its happening gaps."""

    def __init__(self, ct: CompiledTask, kernel: Kernel, actions: Sequence[int],
                 times: Sequence[float], settings: Repair) -> None:
        self.ct, self.kernel, self.settings = ct, kernel, settings
        self.actions = tuple(actions)
        # groups of actions applied epsilon apart: one free time each
        self.first: list[int] = []  # index of each group's first action
        for i, t in enumerate(times):
            # the last action (the skeleton's achiever) has a time of its own
            if i == 0 or t - times[i - 1] > 1.5 * settings.epsilon or i == len(times) - 1:
                self.first.append(i)
        self.x0 = self._gaps(times)
        task = ct.task
        self.pres: list[list[Condition]] = [conjuncts(task.actions[a].precondition)
                                            for a in self.actions]
        self.goal = conjuncts(task.goal)
        self.evals = 0

    def _gaps(self, times: Sequence[float]) -> list[float]:
        """The free gaps [s]: group ``g`` starts ``epsilon + gap`` after the previous group's
        last action (the first group: ``gap`` after 0)."""
        out: list[float] = []
        for g, i in enumerate(self.first):
            prev = -self.settings.epsilon if g == 0 else times[self.first[g] - 1]
            out.append(max(0.0, times[i] - prev - self.settings.epsilon))
        return out

    def _group_end(self, g: int) -> int:
        """Index of group ``g``'s last action."""
        return (self.first[g + 1] if g + 1 < len(self.first) else len(self.actions)) - 1

    def times(self, gaps: Sequence[float], rounded: bool = True) -> list[float]:
        """Every action's time [s] for the gaps [s] between groups (``rounded`` to the plan
        grid, as the plan will be written; the optimiser works unrounded)."""
        eps = self.settings.epsilon
        grid = self.settings.grid if rounded else 0.0
        out: list[float] = []
        t = -eps
        for g, i in enumerate(self.first):
            t = t + eps + max(0.0, gaps[g])
            if grid:
                t = round(t / grid) * grid
            for k in range(i, self._group_end(g) + 1):
                out.append(round(t + (k - i) * eps, 9))
            t = out[-1]
        return out

    def margins(self, gaps: Sequence[float], rounded: bool = True) -> list[float]:
        """How much each condition read holds by (negative: fails by), one per conjunct of
        every precondition in order, of the goal, and each action's distance from events
        beyond the planner's gap; facts count ``+-FAILED``."""
        self.evals += 1
        n = sum(len(p) for p in self.pres) + len(self.goal) + len(self.actions)
        try:
            return self._margins(self.times(gaps, rounded))
        except (InvalidPlanError, ZeroDivisionError, OverflowError, ValueError):
            return [-FAILED] * n

    def _margins(self, times: list[float]) -> list[float]:
        kernel = self.kernel
        log: EventLog = []
        facts, values, active = kernel.settle(0.0, self.ct.init_facts, self.ct.init_values, log)
        out: list[float] = []
        t = 0.0
        for a, at, pre in zip(self.actions, times, self.pres, strict=True):
            facts, values, _ = kernel.advance(t, facts, values, at, log, active)
            facts, values, active = kernel.settle(at, facts, values, log)
            t = at
            out.extend(margin_of(c, facts, values) for c in pre)
            facts, values = self.ct.actions[a].effect(facts, values)
            facts, values, active = kernel.settle(at, facts, values, log)
        out.extend(margin_of(c, facts, values) for c in self.goal)
        gap = self.settings.event_gap
        events = [te for te, i in log if i not in self.ct.rearms]
        for at in times:  # the planner keeps events this far from actions (VAL's quirk)
            near = min((abs(te - at) for te in events), default=math.inf)
            out.append(min(1.0, near - gap))
        return out


def margin_of(cond: Condition, facts: int, values: tuple[float, ...]) -> float:
    """Robustness of ``cond`` (:func:`~artiplan.semantics.walks.robustness`), facts and
    failures as ``+-FAILED``."""
    try:
        r = robustness(cond, facts, values)
    except (ZeroDivisionError, OverflowError, ValueError):
        return -FAILED
    if r != r:
        return -FAILED
    return max(-FAILED, min(FAILED, r))


def repair_times(ct: CompiledTask, kernel: Kernel, actions: Sequence[int],
                 times: Sequence[float], settings: Repair = Repair(),
                 check: Callable[[], None] | None = None,
                 evals: list[int] | None = None) -> list[float] | None:
    """Times [s] at which ``actions`` (in this order) satisfy every precondition and the goal
    by ``settings.margin``, starting from ``times``; None if the optimiser finds none.
    ``evals`` (if given) receives the number of trajectory simulations."""
    prob = TimingProblem(ct, kernel, actions, times, settings)
    try:
        return _solve(prob, settings, check)
    finally:
        if evals is not None:
            evals.append(prob.evals)


def _solve(prob: TimingProblem, settings: Repair,
           check: Callable[[], None] | None) -> list[float] | None:
    if not prob.first:
        return None
    mu = settings.margin
    start = prob.margins(prob.x0)
    if min(start) >= mu:
        return prob.times(prob.x0)
    if min(start) <= -FAILED:
        return None
    x = _feasible_point(prob, settings, start, check)
    if x is not None and min(prob.margins(x)) >= mu:
        return prob.times(x)
    return None


def _feasible_point(prob: TimingProblem, settings: Repair, margins: list[float],
                    check: Callable[[], None] | None) -> list[float] | None:
    """A point ``x >= 0`` where every margin is >= 1.5 * margin, by sequential quadratic
    programming on the feasibility problem (as SLSQP with a zero objective).

    Each step minimises ``d' B d / 2`` subject to ``c + J d >= 0`` and ``x + d >= 0``
    (``c``: the margins less 2 * margin; ``J``: their forward-difference Jacobian; every
    condition linearised, held ones too, so a window's far side is seen before it is
    crossed). ``B`` is a damped BFGS estimate of the curvature of the conditions weighted by
    the step's multipliers (a distance that must fall below a radius curves: without it the
    steps zigzag past its minimum). The step is halved until the total shortfall drops by a
    share of it (Armijo). None when a step gains nothing or the budget of trajectory
    simulations is spent."""
    mu = settings.margin
    x = list(prob.x0)
    n = len(x)
    evals = prob.evals
    hess = [[1.0 if i == j else 0.0 for j in range(n)] for i in range(n)]
    c = [m - 2.0 * mu for m in margins]
    last: tuple[list[float], list[float], list[list[float]]] | None = None
    while prob.evals - evals + n + 1 <= settings.max_evals:
        if check is not None:
            check()
        jac = _jacobian(prob, x, c, 2.0 * mu)
        if last is not None:
            _bfgs(hess, last, x, jac)
        rows = [(a, -v) for a, v in zip(jac, c, strict=True)]
        rows.extend(([1.0 if k == j else 0.0 for k in range(n)], -x[j]) for j in range(n))
        d, lam = _qp_step(hess, rows)
        now = _shortfall(c)
        alpha = 1.0
        for _ in range(_HALVINGS):
            trial = [max(0.0, xj + alpha * dj) for xj, dj in zip(x, d, strict=True)]
            m = prob.margins(trial, rounded=False)
            if min(m) >= 1.5 * mu:
                return trial
            ct = [v - 2.0 * mu for v in m]
            # Armijo on the L1 merit: a step that solves its QP predicts the whole shortfall
            # gone, so at least a 1e-4 share of it must go (creeping at a corner stops)
            if _shortfall(ct) <= (1.0 - 1e-4 * alpha) * now:
                last = (x, lam[:len(c)], jac)
                x, c = trial, ct
                break
            alpha *= 0.5
        else:
            return None
    return None


def _shortfall(c: Sequence[float]) -> float:
    """How far the conditions are from holding, summed (an L1 merit)."""
    return sum(-v for v in c if v < 0.0)


def _jacobian(prob: TimingProblem, x: list[float], c: list[float],
              shift: float) -> list[list[float]]:
    """Forward differences of ``c = margins(x) - shift``, a row per condition."""
    jac: list[list[float]] = [[] for _ in c]
    for j in range(len(x)):
        h = _STEP * max(1.0, abs(x[j]))
        xh = list(x)
        xh[j] += h
        for row, v, v0 in zip(jac, prob.margins(xh, rounded=False), c, strict=True):
            row.append((v - shift - v0) / h)
    return jac


def _bfgs(hess: list[list[float]], last: tuple[list[float], list[float], list[list[float]]],
          x: list[float], jac: list[list[float]]) -> None:
    """Powell-damped BFGS update of ``hess`` in place, from the step ``x_old -> x`` and the
    change of the Lagrangian's gradient ``-sum(lam * grad c)`` over it (``last``: the old
    point, the step's multipliers and the old Jacobian)."""
    x_old, lam, jac_old = last
    n = len(x)
    s = [a - b for a, b in zip(x, x_old, strict=True)]
    y = [0.0] * n
    for li, row, row_old in zip(lam, jac, jac_old, strict=True):
        if li:
            for k in range(n):
                y[k] -= li * (row[k] - row_old[k])
    bs = [sum(hess[i][k] * s[k] for k in range(n)) for i in range(n)]
    sbs = sum(a * b for a, b in zip(s, bs, strict=True))
    sy = sum(a * b for a, b in zip(s, y, strict=True))
    if sbs <= 1e-300:
        return
    if sy < 0.2 * sbs:  # Powell's damping keeps the estimate positive definite
        theta = 0.8 * sbs / (sbs - sy)
        y = [theta * a + (1.0 - theta) * b for a, b in zip(y, bs, strict=True)]
        sy = sum(a * b for a, b in zip(s, y, strict=True))
    if sy <= 1e-300:
        return
    for i in range(n):
        for k in range(n):
            hess[i][k] += y[i] * y[k] / sy - bs[i] * bs[k] / sbs


def _qp_step(hess: list[list[float]],
             rows: Sequence[tuple[Sequence[float], float]]) -> tuple[list[float], list[float]]:
    """The ``d`` minimising ``d' B d / 2`` (nearly) with ``a . d >= b`` for every ``(a, b)``
    of ``rows``, and the rows' multipliers; by Hildreth's dual coordinate ascent after the
    change of variables ``z = L' d`` (``B = L L'``), each row scaled to unit length and
    softened by ``_SOFT`` (conflicting rows give a compromise, not a divergence). Rows with
    ``a = 0`` are left out: no step changes them to first order."""
    n = len(hess)
    low = _cholesky(hess)
    unit: list[tuple[list[float], float, float, int]] = []
    for i, (a, b) in enumerate(rows):
        g = _solve_lower(low, list(a))  # a . d = a . L'^-1 z = (L^-1 a) . z
        norm = math.sqrt(sum(v * v for v in g))
        if norm > 0.0 and math.isfinite(norm) and math.isfinite(b):
            unit.append(([v / norm for v in g], b / norm, norm, i))
    z = [0.0] * n
    lam = [0.0] * len(unit)
    tol = 1e-12 * (1.0 + max((abs(u[1]) for u in unit), default=0.0))
    for _ in range(_SWEEPS):
        biggest = 0.0
        for i, (a, b, _, _) in enumerate(unit):
            az = sum(ak * zk for ak, zk in zip(a, z, strict=True))
            new = max(0.0, lam[i] + (b - az - _SOFT * lam[i]) / (1.0 + _SOFT))
            step = new - lam[i]
            if step:
                lam[i] = new
                for k in range(n):
                    z[k] += step * a[k]
                biggest = max(biggest, abs(step))
        if biggest <= tol:
            break
    d = _solve_upper(low, z)
    mult = [0.0] * len(rows)
    for li, (_, _, norm, i) in zip(lam, unit, strict=True):
        mult[i] = li / norm
    return d, mult


def _cholesky(a: list[list[float]]) -> list[list[float]]:
    """Lower-triangular ``L`` with ``L L' = a`` (``a`` symmetric positive definite; a
    pivot that is not positive is floored, so a worn estimate still gives a step)."""
    n = len(a)
    low = [[0.0] * n for _ in range(n)]
    for i in range(n):
        for j in range(i + 1):
            s = a[i][j] - sum(low[i][k] * low[j][k] for k in range(j))
            if i == j:
                low[i][i] = math.sqrt(max(s, 1e-12))
            else:
                low[i][j] = s / low[j][j]
    return low


def _solve_lower(low: list[list[float]], b: list[float]) -> list[float]:
    """``L^-1 b`` for lower-triangular ``L``."""
    out: list[float] = []
    for i, row in enumerate(low):
        out.append((b[i] - sum(row[k] * out[k] for k in range(i))) / row[i])
    return out


def _solve_upper(low: list[list[float]], b: list[float]) -> list[float]:
    """``L'^-1 b`` for lower-triangular ``L``."""
    n = len(low)
    out = [0.0] * n
    for i in reversed(range(n)):
        out[i] = (b[i] - sum(low[k][i] * out[k] for k in range(i + 1, n))) / low[i][i]
    return out


#: Forward-difference step [s] per second of gap (at least this many seconds).
_STEP = 1e-7
#: Step halvings tried before a linearisation is given up.
_HALVINGS = 8
#: Sweeps of Hildreth's method per step, and its softening of the rows.
_SWEEPS = 300
_SOFT = 1e-9


__all__ = ["Repair", "TimingProblem", "margin_of", "repair_times"]
