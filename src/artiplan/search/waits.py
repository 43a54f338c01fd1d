"""The planner's waits: how long a search node lets time pass, on top of the kernel.

A wait ends on the plan grid (``tol.grid``, the 6 decimals of a plan file), at least one grid
step after the root that ends it, so the printed plan is the plan that was searched and every
comparison that became true holds with a margin:

- :meth:`Waits.next` - until just after the next time a watched condition may change;
- :meth:`Waits.until` - until a condition holds (a goal group, the goal), then ``margin``
  seconds more while it keeps holding.
"""

from __future__ import annotations

import math

from artiplan.semantics.compiled import CompiledTask, CondFn
from artiplan.semantics.flow import STILL, Flow
from artiplan.semantics.kernel import EventLog, InvariantError, Kernel, Values

#: (time [s], facts, values, active processes) at the end of a wait.
Arrival = tuple[float, int, Values, tuple[int, ...]]


def comparison_holds(ct: CompiledTask, cid: int, values: Values, snapped: bool) -> bool:
    """Truth of comparison ``cid`` at ``values``: ``snapped`` (as a strict task reads its
    goal), else with the task's tolerances (as invariants are read)."""
    item = ct.comps.items[cid]
    p = STILL.poly(item, values)
    return p is not None and (ct.tol.snapped if snapped else ct.tol.point)(item.op, p[0])


def grid_after(t: float, grid: float) -> float:
    """The first grid time at least one grid step after ``t`` [s]."""
    return round(math.ceil((t + grid) / grid - 1e-6) * grid, 9)


def floor_grid(t: float, grid: float) -> float:
    """The last grid time at or before ``t`` [s]."""
    return round(math.floor(t / grid + 1e-6) * grid, 9)


def ceil_grid(t: float, grid: float) -> float:
    """The first grid time at or after ``t`` [s]."""
    return round(math.ceil(t / grid - 1e-6) * grid, 9)


class Waits:
    """Waits over one kernel."""

    #: How far [s] one wait looks ahead along a flow without a closed form: integrating to the
    #: kernel's own horizon (an hour) for every wait made nonlinear domains 10-20x slower; a
    #: longer wait is made of several (each stop is then a state like any other).
    LOOKAHEAD = 60.0

    def __init__(self, kernel: Kernel, lead: float = 0.0) -> None:
        self.kernel = kernel
        self.grid = kernel.ct.tol.grid
        #: A wait that would break an invariant stops this long [s] before (time for two
        #: actions that save it, ``event_gap`` apart), else at the last grid time before.
        self.lead = lead

    #: How many look-aheads in a row without a change :meth:`until` takes before giving up.
    BLIND_LOOKAHEADS = 5

    def _change(self, values: Values, flow: Flow, comps: tuple[int, ...]) -> float | None:
        """``Kernel.next_change``, at most :attr:`LOOKAHEAD` ahead on numeric flows."""
        if flow.exact or not comps:
            return self.kernel.next_change(values, flow, comps)
        return self.kernel.next_change(values, flow, comps, self.LOOKAHEAD)

    def next(self, t: float, facts: int, values: Values, log: EventLog, active: tuple[int, ...],
             margin: float = 0.0, goal_comps: frozenset[int] = frozenset()) -> Arrival | None:
        """Until just after the next time a watched condition may change truth value.

        When that change makes goal comparisons (``goal_comps``) true, the wait runs on for
        ``margin`` [s] while they keep holding, so an action there sees them with a margin.
        """
        k = self.kernel
        flow = k.flow_of(active, values)
        if not flow.moving:
            return None
        dt = self._change(values, flow, k.comps_for(flow, "watched"))
        if dt is None or not math.isfinite(dt):
            return None
        end = grid_after(t + dt, self.grid)
        end, facts2, values2, act = self._advance(t, facts, values, end, log, active)
        if margin > 0.0 and goal_comps:
            newly = frozenset(c for c in goal_comps
                              if not self._holds(c, values) and self._holds(c, values2))
            if newly:
                def cond(_f: int, v: Values) -> bool:
                    return all(self._holds(c, v) for c in newly)

                return self._margin(end, facts2, values2, cond, newly, log, act, margin)
        return end, facts2, values2, act

    def _advance(self, t: float, facts: int, values: Values, until: float, log: EventLog,
                 active: tuple[int, ...]) -> Arrival:
        """Let time pass to ``until`` [s]; if an invariant would fail on the way, stop
        :attr:`lead` before (or at the last grid time before; raise if that is no later than
        ``t`` + a grid step)."""
        trial: EventLog = []
        try:
            out = self.kernel.advance(t, facts, values, until, trial, active)
        except InvariantError as exc:
            end = floor_grid(exc.time - self.lead, self.grid)
            if end <= t + self.grid:
                end = floor_grid(exc.time, self.grid)
            if end <= t + self.grid or end >= until:
                raise
            trial = []
            out = self.kernel.advance(t, facts, values, end, trial, active)
            until = end
        log.extend(trial)
        return (until, *out)

    def closing(self, values: Values, active: tuple[int, ...], comps: frozenset[int]) -> bool:
        """True when one of ``comps`` holds now and reads a changing fluent (it may close)."""
        flow = self.kernel.flow_of(active, values)
        items = self.kernel.ct.comps.items
        return any(items[c].fluents & flow.changing and self._holds(c, values) for c in comps)

    def before(self, t: float, facts: int, values: Values, log: EventLog,
               active: tuple[int, ...], comps: frozenset[int],
               triggers: frozenset[int] = frozenset(), gap: float = 0.0) -> Arrival | None:
        """Until the last grid time before one of ``comps`` that holds now fails, or ``gap``
        [s] before one of ``triggers`` (an event's comparisons) changes (None if nothing
        will, or that time is within a grid step)."""
        k = self.kernel
        flow = k.flow_of(active, values)
        items = k.ct.comps.items
        holding = tuple(sorted(c for c in comps if items[c].fluents & flow.changing
                               and self._holds(c, values)))
        moving = tuple(sorted(c for c in triggers if items[c].fluents & flow.changing))
        ends: list[float] = []
        for watch, early in ((holding, 0.0), (moving, gap)):
            dt = self._change(values, flow, watch) if watch else None
            if dt is not None and math.isfinite(dt):
                ends.append(floor_grid(t + dt - early, self.grid))
        end = min(ends, default=math.inf)
        if end == math.inf or end <= t + self.grid:
            return None
        return self._advance(t, facts, values, end, log, active)

    def delta(self, t: float, facts: int, values: Values, log: EventLog,
              active: tuple[int, ...], step: float) -> Arrival | None:
        """Until the next multiple of ``step`` [s] at least a grid step after ``t`` (multiples
        of one step, so that paths meet in the same states)."""
        if not self.kernel.flow_of(active, values).moving:
            return None
        end = ceil_grid((math.floor((t + self.grid) / step + 1e-9) + 1) * step, self.grid)
        return self._advance(t, facts, values, end, log, active)

    def hold(self, t: float, facts: int, values: Values, log: EventLog,
             active: tuple[int, ...], seconds: float) -> Arrival | None:
        """For ``seconds`` [s] (to the grid time at or after ``t + seconds``, at least a grid
        step after ``t``), or None if nothing moves."""
        if not self.kernel.flow_of(active, values).moving:
            return None
        end = max(ceil_grid(t + seconds, self.grid), grid_after(t, self.grid))
        return self._advance(t, facts, values, end, log, active)

    def until(self, t: float, facts: int, values: Values, cond: CondFn,
              cond_comps: frozenset[int], log: EventLog, active: tuple[int, ...],
              max_steps: int = 64, margin: float = 0.0,
              horizon: float = math.inf) -> Arrival | None:
        """Until ``cond`` holds (then ``margin`` [s] more while it keeps holding), or None.

        Stops at every change of the dynamics or of ``cond``'s comparisons; gives up after
        ``max_steps`` of them, when nothing moves any more, or past ``horizon`` [s].
        """
        k = self.kernel
        act = active
        blind = 0
        for _ in range(max_steps):
            flow = k.flow_of(act, values)
            if not flow.moving:
                return None
            dt = self._change(values, flow, self._watch(flow, cond_comps, facts))
            if dt is None and not flow.exact and blind < self.BLIND_LOOKAHEADS \
                    and all(math.isfinite(v) for v in flow.values(values, self.LOOKAHEAD)):
                dt, blind = self.LOOKAHEAD, blind + 1  # nothing within the look-ahead: on
            else:
                blind = 0
            if dt is None or not math.isfinite(dt):
                return None
            t_next = grid_after(t + dt, self.grid)
            if t_next > horizon:
                return None
            reached, facts, values, act = self._advance(t, facts, values, t_next, log, act)
            if reached < t_next:  # stopped before an invariant fails: the last chance to act
                return reached, facts, values, act
            t = t_next
            if cond(facts, values):
                return self._margin(t, facts, values, cond, cond_comps, log, act, margin)
        return None

    def _holds(self, cid: int, values: Values) -> bool:
        """Truth of goal comparison ``cid`` at ``values`` (as the goal is read)."""
        return comparison_holds(self.kernel.ct, cid, values, self.kernel.ct.strict)

    def _watch(self, flow: Flow, cond_comps: frozenset[int], facts: int) -> tuple[int, ...]:
        """``cond``'s comparisons on changing fluents, and those that can change the dynamics
        from ``facts`` (not re-arms: they change nothing a wait is for)."""
        items = self.kernel.ct.comps.items
        own = [c for c in cond_comps if items[c].fluents & flow.changing]
        return tuple(sorted(set(own) | set(self.kernel.comps_for(flow, "spaced", facts))))

    def _margin(self, t: float, facts: int, values: Values, cond: CondFn,
                cond_comps: frozenset[int], log: EventLog, active: tuple[int, ...],
                margin: float) -> Arrival:
        if margin <= 0.0:
            return t, facts, values, active
        k = self.kernel
        flow = k.flow_of(active, values)
        if not flow.moving:
            return t, facts, values, active
        dt = k.next_change(values, flow, self._watch(flow, cond_comps, facts), 2.0 * margin)
        step = margin if dt is None else min(margin, 0.5 * dt)
        end = round(math.floor((t + step) / self.grid) * self.grid, 9)
        if end <= t:
            return t, facts, values, active
        trial: EventLog = []
        f2, v2, a2 = k.advance(t, facts, values, end, trial, active)
        if not cond(f2, v2):
            return t, facts, values, active
        log.extend(trial)
        return end, f2, v2, a2
