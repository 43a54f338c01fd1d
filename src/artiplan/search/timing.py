"""Timing repair: the happening times of a plan skeleton, solved for, not searched on a grid.

A search on a grid of times (free waits of ``delta`` seconds) finds the right actions in the
right order long before it finds the right times: a car that must stop inside a 0.2 m window
at 36 m/s needs its braking time to the millisecond. Given the skeleton (the actions of a
search path, in order, with their grid times, and the action that should end it), this module
moves the times to satisfy every precondition, the goal, and the planner's distance from
events, with the kernel's exact trajectory as the model:

    margins(times) = [robustness(c) for each condition c read]

kept >= 2 * margin by scipy's SLSQP (finite differences) over the gaps between happenings,
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

    # imported only now: most repairs end above (scipy.optimize costs ~0.6-1 s CPU to import)
    from scipy.optimize import minimize

    found: list[list[float]] = []

    def cons(x: Sequence[float]) -> list[float]:
        if check is not None:
            check()
        margins = prob.margins(x, rounded=False)
        if min(margins) >= 1.5 * mu:  # feasible with room for the rounding: done
            found.append(list(x))
            raise _Feasible
        return [m - 2.0 * mu for m in margins]

    # find a point where every margin holds (SLSQP linearises them all, held ones too, so
    # a window's far side is seen before it is crossed); the first such point ends it
    x0 = list(prob.x0)
    try:
        minimize(lambda x: 0.0, x0, method="SLSQP", bounds=[(0.0, None)] * len(x0),
                 constraints=[{"type": "ineq", "fun": cons}],
                 options={"maxiter": settings.max_evals // max(2, len(x0) + 1),
                          "ftol": 1e-12})
    except _Feasible:
        pass
    except (ValueError, FloatingPointError, ArithmeticError):
        return None
    for x in found:
        if min(prob.margins(x)) >= mu:
            return prob.times(x)
    return None


class _Feasible(Exception):
    """Raised inside the optimiser to stop it at the first feasible point."""


__all__ = ["Repair", "TimingProblem", "margin_of", "repair_times"]
