"""The numeric relaxation's second-order terms (:mod:`artiplan.search.numeric` uses them).

Two things a relaxation over single comparisons misses when a position is steered through its
speed by a control (:mod:`artiplan.search.motion`):

- **time labels**: a process's time to a threshold, read with the controls as they are now,
  hides that more actions would raise the acceleration; a deadline then prunes states that
  are not lost. The labels take the most favourable ends of the controls' levels
  (:meth:`SecondOrder.corners`); the costs keep the current ones.
- **joint goals**: a conjunction that wants the position in a box with the speed in a band
  is costed at once (:meth:`SecondOrder.joint`): the control steps and the weighted time of
  the least profile that makes it by the conjunction's deadline, instead of its comparisons'
  costs one by one. The profile also says which way the control must go first and how long
  the controls may stay as they are (:class:`Steering`: preferred actions, the wait the
  search may take).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable

from artiplan.pddl.task import Comparison, Condition, Task
from artiplan.records import dataclass, field
from artiplan.search.motion import (
    MotionGoal,
    find_controls,
    find_motions,
    motion_goals,
    speed_limits,
)
from artiplan.semantics.compiled import CompiledTask
from artiplan.semantics.walks import conjuncts, fluents_of

Values = tuple[float, ...]
#: ``flow(values, active)``: d(fluent)/dt of every changing fluent.
FlowFn = Callable[[Values, tuple[int, ...]], dict[int, float]]
#: Values with the controls at the ends of their levels, and the flow there.
Corner = tuple[Values, dict[int, float]]


@dataclass
class Steering:
    """What a conjunction's motion goals ask of the controls in one state: steps in all, the
    actions that move a control the way it must go first, and how long [s] the controls may
    stay as they are before the next step (inf: no such wait)."""

    steps: int = 0
    actions: set[int] = field(default_factory=set)
    hold: float = math.inf


class SecondOrder:
    """The controls and motions of a task, and the terms they add to the relaxation."""

    def __init__(self, task: Task, flow: FlowFn,
                 active_fn: Callable[[int, Values], tuple[int, ...]] | None,
                 time_weight: float, base: int) -> None:
        """``flow``: the relaxation's rates; ``active_fn(facts, values)``: the processes that
        run at some values (None: those of the state); ``base``: the node id of the first
        condition (conditions come after the fact literals)."""
        self.task, self.flow, self.active_fn = task, flow, active_fn
        self.time_weight, self.base = time_weight, base
        self.controls = find_controls(task)
        self.motions = find_motions(task, self.controls)
        self.limits = speed_limits(task, {m.y for m in self.motions.values()}) \
            if self.motions else []
        self.movers: dict[int, set[int]] = {}  # fluent -> the fluents its rates read
        for p in task.processes:
            for ce in p.continuous:
                self.movers.setdefault(ce.fluent, set()).update(fluents_of(ce.rate))

    def controls_of(self, reads: frozenset[int]) -> tuple[int, ...]:
        """The controls a rate reading ``reads`` depends on, directly or through the rates of
        the fluents it reads (the acceleration behind a speed)."""
        second = set().union(*(self.movers.get(j, set()) for j in reads))
        return tuple(sorted(f for f in reads | second if f in self.controls))

    def goals(self, cond: Condition, cond_index: Callable[[Comparison], int]
              ) -> tuple[MotionGoal, ...]:
        """The motion goals of a conjunction (none without motions)."""
        if not self.motions:
            return ()
        return tuple(motion_goals(conjuncts(cond), cond_index, self.motions, self.limits))

    def corners(self, controls: tuple[int, ...], values: Values, active: tuple[int, ...],
                cache: dict[tuple[int, ...], list[Corner]]) -> list[Corner]:
        """``values`` with ``controls`` (the first three) at either end of their levels, and
        the flows there; once per state (``cache``)."""
        found = cache.get(controls)
        if found is None:
            found = []
            ends = ((self.controls[u].levels[0], self.controls[u].levels[-1])
                    for u in controls[:3])
            for at in itertools.product(*ends):
                moved = list(values)
                for u, level in zip(controls, at, strict=False):
                    moved[u] = level
                found.append((tuple(moved), self.flow(tuple(moved), active)))
            cache[controls] = found
        return found

    def joint(self, goals: tuple[MotionGoal, ...], pre: tuple[int, ...], facts: int,
              values: Values, active: tuple[int, ...], cost: list[float],
              left: dict[int, float], steer: Steering) -> tuple[float, float] | None:
        """(extra cost, time [s]) of a conjunction's motion goals, costed jointly (control
        steps plus the time's weight, in place of the costs ``cost`` of their comparisons)
        by the deadlines among ``pre`` (``left``: time left per deadline condition); None if
        one cannot be made by them. ``steer`` receives what they ask of the controls."""
        base = self.base
        deadline = min((left[q - base] for q in pre if q - base in left), default=math.inf)
        extra, time = 0.0, 0.0
        for g in goals:
            y = g.motion.y

            def accel(v: Values, y: int = y, k: float = g.motion.k) -> float:
                running = active if self.active_fn is None else self.active_fn(facts, v)
                return k * self.flow(v, running).get(y, 0.0)

            est = g.estimate(values, accel, deadline,
                             active if self.active_fn is None else facts)
            if est is None:
                continue  # the motion does not run: the comparisons as they are
            if est.time == math.inf:
                return None
            extra += est.steps + self.time_weight * est.time - \
                sum(cost[base + k] for k in g.conds)
            time = max(time, est.time)
            steer.steps += est.steps
            if est.hold > 0.0:
                steer.hold = min(steer.hold, est.hold)
            u = g.motion.control
            at = u.index(values[u.fluent])
            if est.first != at:
                steer.actions.update(u.raise_by if est.first > at else u.lower_by)
        return extra, time


def applicable(ct: CompiledTask, a: int, facts: int, values: Values) -> bool:
    """True when action ``a`` may be applied in the state."""
    act = ct.actions[a]
    return not facts & act.forb and not act.req & ~facts and act.pre(facts, values)


__all__ = ["Corner", "SecondOrder", "Steering", "applicable"]
