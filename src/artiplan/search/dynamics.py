"""Letting time pass in the search: events at their exact times, waits to critical times.

Rules (VAL's, as the planner needs them):

- Processes run while their precondition holds; which ones run just after a time point is decided
  on the *right limit*, with the validator's rules (:mod:`artiplan.search.rightlimit`), so a
  process whose precondition becomes true as an angle leaves a boundary starts at once. The set
  is kept through waits and recomputed only where the validator recomputes it: at events and
  at actions.
- An event fires at the earliest time its precondition becomes true: the exact root of the
  comparison, found with the polynomial flow (:mod:`artiplan.search.flow`). Events cascade to a
  fixpoint; each event fires at most once per time point.
- Waits end on a grid of ``grid`` seconds (1e-6: the 6 decimals of a plan file), at least one grid
  step after the root that ends them, so the printed plan is the plan that was searched and every
  comparison that became true holds with a margin.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from artiplan.search.compiled import VAL_READING, CompiledTask, CondFn
from artiplan.search.flow import (
    DT_MIN,
    STILL,
    Flow,
    FlowShape,
    advance_values,
    comparison_poly,
    compute_flow,
    first_root,
    flow_shape,
)
from artiplan.search.rightlimit import RightLimit

Values = tuple[float, ...]
EventLog = list[tuple[float, int]]


class ZenoError(RuntimeError):
    """Events keep firing without time passing (a modelling error of the task)."""


@dataclass(frozen=True)
class DynamicsConfig:
    """Numeric settings of the search's simulator.

    Attributes:
        grid: Happening times are multiples of this [s] (plan files print 6 decimals).
        fallback_step: Longest step [s] when rates are not polynomial (counted in the stats).
        max_cascade: Most rounds of events at one time point before declaring a Zeno loop.
    """

    grid: float = 1e-6
    fallback_step: float = 0.1
    max_cascade: int = 200


def grid_after(t: float, grid: float) -> float:
    """The first grid time at least one grid step after ``t`` [s]."""
    return round(math.ceil((t + grid) / grid - 1e-6) * grid, 9)


def ceil_grid(t: float, grid: float) -> float:
    """The first grid time at or after ``t`` [s]."""
    return round(math.ceil(t / grid - 1e-6) * grid, 9)


@dataclass
class Dynamics:
    """The search's simulator over a compiled task, with caches and counters."""

    ct: CompiledTask
    config: DynamicsConfig = field(default_factory=DynamicsConfig)
    counters: dict[str, int] = field(default_factory=lambda: {"fallback_steps": 0, "events": 0})

    def __post_init__(self) -> None:
        members: dict[int, list[int]] = {}
        for proc in self.ct.processes:
            members.setdefault(proc.pre_class, []).append(proc.index)
        self._class_members = [members[c] for c in range(len(members))]
        heads = [self.ct.processes[m[0]] for m in self._class_members]
        self._class_buckets, self._class_always = _buckets(
            [_ClassHead(c, h.req) for c, h in enumerate(heads)])
        self._event_buckets, self._event_always = _buckets(self.ct.events)
        self._const_rates = [
            all(lin is not None and not lin[0] for _, lin, _ in p.rates) for p in self.ct.processes
        ]
        self._flow_cache: dict[tuple[int, ...], Flow] = {}
        self._shapes: dict[tuple[int, ...], FlowShape] = {}
        self._last_flow: tuple[tuple[int, ...], Values, Flow] | None = None
        self._split_cache: dict[tuple[int, ...], tuple[LinearRows | None, tuple[int, ...]]] = {}
        self.right = RightLimit(self.ct)
        self.counters.setdefault("boundary_flows", 0)
        self._comp_cache: dict[tuple[frozenset[int], str], tuple[int, ...]] = {}

    # ------------------------------------------------------------------ processes and flows
    def active(self, facts: int, values: Values) -> tuple[int, ...]:
        """Indices of the processes whose precondition holds."""
        procs = self.ct.processes
        out: list[int] = []
        for cls in _candidates(facts, self._class_buckets, self._class_always):
            members = self._class_members[cls]
            head = procs[members[0]]
            if not facts & head.forb and head.pre(facts, values):
                out.extend(members)
        out.sort()
        return tuple(out)

    def flow_of(self, active: tuple[int, ...], values: Values) -> Flow:
        """The flow while exactly ``active`` run (cached when their rates are constant)."""
        cached = self._flow_cache.get(active)
        if cached is not None:
            return cached
        last = self._last_flow
        if last is not None and last[0] == active and last[1] is values:
            return last[2]
        shape = self._shapes.get(active)
        if shape is None:
            shape = self._shapes[active] = flow_shape(self.ct.processes, active)
        flow = compute_flow(self.ct.processes, active, values, self.config.fallback_step, shape)
        if all(self._const_rates[i] for i in active):
            self._flow_cache[active] = flow
        self._last_flow = (active, values, flow)
        return flow

    def flow(self, facts: int, values: Values) -> tuple[tuple[int, ...], Flow]:
        """Active processes and their flow just after now (the validator's right limit)."""
        act = self.active(facts, values)
        settled = self.right.settle_active(
            facts, values, act, lambda a: self.flow_of(a, values), self._changing)
        if settled != act:
            self.counters["boundary_flows"] += 1
        return settled, self.flow_of(settled, values)

    def _changing(self, active: tuple[int, ...]) -> frozenset[int]:
        shape = self._shapes.get(active)
        if shape is None:
            shape = self._shapes[active] = flow_shape(self.ct.processes, active)
        return frozenset(shape.b)

    def comps_for(self, flow: Flow, kind: str) -> tuple[int, ...]:
        """Comparisons of ``kind`` ('watched' or 'dynamic') that read a moving fluent."""
        key = (frozenset(flow.coeffs), kind)
        found = self._comp_cache.get(key)
        if found is None:
            pool = self.ct.watched if kind == "watched" else self.ct.dynamic
            ids: set[int] = set()
            for f in flow.coeffs:
                ids.update(c for c in self.ct.fluent_comps.get(f, ()) if c in pool)
            found = self._comp_cache[key] = tuple(sorted(ids))
        return found

    def next_change(
        self, values: Values, flow: Flow, comps: tuple[int, ...], horizon: float = math.inf
    ) -> float | None:
        """Earliest dt > 0 [s] at which one of ``comps`` may change truth value."""
        rows, general = self._split(comps)
        best = horizon
        found = False
        if rows is not None:
            if flow.degree <= 2:
                r = rows.first_root(values, flow, self.ct.n_fluents, best)
                if r is not None:
                    best, found = r, True
            else:
                general = tuple(rows.ids) + general
        items = self.ct.comps.items
        for cid in general:
            poly = comparison_poly(items[cid], values, flow)
            if poly is None:  # not a polynomial: a documented fallback step
                if self.config.fallback_step < best:
                    best, found = self.config.fallback_step, True
                    self.counters["fallback_steps"] += 1
                continue
            root = first_root(poly, best)
            if root is not None:
                best, found = root, True
        if flow.valid_for < best:
            self.counters["fallback_steps"] += 1
            return flow.valid_for
        return best if found else None

    def _split(self, comps: tuple[int, ...]) -> tuple[LinearRows | None, tuple[int, ...]]:
        """Comparisons on one fluent (solved together with numpy) and the others."""
        found = self._split_cache.get(comps)
        if found is None:
            items = self.ct.comps.items
            single = [c for c in comps if items[c].linear is not None
                      and len(items[c].linear[0]) == 1]  # type: ignore[index]
            rest = tuple(c for c in comps if c not in set(single))
            found = (LinearRows.of(single, items) if single else None, rest)
            if len(self._split_cache) < 100_000:
                self._split_cache[comps] = found
        return found

    # ------------------------------------------------------------------ events and time
    def settle(
        self, t: float, facts: int, values: Values, log: EventLog
    ) -> tuple[int, Values, tuple[int, ...]]:
        """Fire every triggered event at time ``t`` [s], cascading to a fixpoint.

        Returns the facts, values and the processes active just after ``t``.
        """
        events = self.ct.events
        fired: set[int] = set()
        for _ in range(self.config.max_cascade):
            act, flow = self.flow(facts, values)
            near = self.right.near_comps(values)
            edge = {e for c in near for e in self.right.events_of.get(c, ())} if near else set()
            changing = self._changing(act) if edge else frozenset()
            triggered = []
            for i in _candidates(facts, self._event_buckets, self._event_always):
                ev = events[i]
                if facts & ev.forb:
                    continue
                if ev.pre(facts, values) or (
                    i in edge
                    and self.right.event_reads[i] & changing
                    and self.right.holds_after(self.ct.task.events[i].precondition, facts,
                                               values, flow)
                ):
                    triggered.append(i)
            if any(i in fired for i in triggered):
                raise ZenoError(f"an event is triggered twice at t={t:.6f}")
            if not triggered:
                return facts, values, act
            for i in sorted(triggered):
                facts, values = events[i].effect(facts, values)
                fired.add(i)
                log.append((t, i))
                self.counters["events"] += 1
        raise ZenoError(f"events keep firing at t={t:.6f}: the task has an event loop")

    def advance(
        self, t: float, facts: int, values: Values, until: float, log: EventLog,
        active: tuple[int, ...],
    ) -> tuple[int, Values, tuple[int, ...]]:
        """Let time pass from ``t`` to ``until`` [s] with ``active`` running from ``t``.

        Events fire at their exact times, and the active processes are recomputed there (as the
        validator does); reaching ``until`` itself changes nothing unless it is such a time.
        """
        act = active
        for _ in range(1_000_000):
            if until - t <= 0.0:
                return facts, values, act
            flow = self.flow_of(act, values)
            if not flow.moving:
                return facts, values, act
            dt = self.next_change(values, flow, self.comps_for(flow, "dynamic"), until - t)
            if dt is None or t + dt >= until:
                values = advance_values(values, flow, until - t)
                if dt is not None and t + dt >= until - 1e-12:  # critical exactly at until
                    facts, values, act = self.settle(until, facts, values, log)
                return facts, values, act
            values = advance_values(values, flow, dt)
            t += dt
            facts, values, act = self.settle(t, facts, values, log)
        raise ZenoError(f"time cannot pass beyond t={t:.6f}")

    def wait_next(
        self, t: float, facts: int, values: Values, log: EventLog, active: tuple[int, ...],
        margin: float = 0.0, goal_comps: frozenset[int] = frozenset(),
    ) -> tuple[float, int, Values, tuple[int, ...]] | None:
        """Wait until just after the next time a watched condition may change truth value.

        When that change makes goal comparisons (``goal_comps``) true, the wait runs on for
        ``margin`` [s] while they keep holding, so an action there sees them with a margin.
        """
        flow = self.flow_of(active, values)
        if not flow.moving:
            return None
        dt = self.next_change(values, flow, self.comps_for(flow, "watched"))
        if dt is None:
            return None
        until = grid_after(t + dt, self.config.grid)
        facts2, values2, act = self.advance(t, facts, values, until, log, active)
        if margin > 0.0 and goal_comps:
            newly = frozenset(c for c in goal_comps
                              if not self._comp_holds(c, values) and self._comp_holds(c, values2))
            if newly:
                def cond(_f: int, v: Values) -> bool:
                    return all(self._comp_holds(c, v) for c in newly)

                return self._with_margin(until, facts2, values2, cond, newly, log, act, margin)
        return until, facts2, values2, act

    def _comp_holds(self, cid: int, values: Values) -> bool:
        """Truth of comparison ``cid`` at ``values`` (VAL's reading)."""
        item = self.ct.comps.items[cid]
        p = comparison_poly(item, values, STILL)
        if p is None:
            return False
        d = p[0] + VAL_READING.offset(item.op)
        return {">": d > 0, ">=": d >= 0, "<": d < 0, "<=": d <= 0}.get(item.op, abs(p[0]) <=
                                                                        VAL_READING.eps)

    def wait_until(
        self, t: float, facts: int, values: Values, cond: CondFn, cond_comps: frozenset[int],
        log: EventLog, active: tuple[int, ...], max_steps: int = 64, margin: float = 0.0,
        horizon: float = math.inf,
    ) -> tuple[float, int, Values, tuple[int, ...]] | None:
        """Wait until ``cond`` holds (then ``margin`` [s] more if it keeps holding), or None.

        Stops at the first change of the dynamics or of ``cond``'s comparisons; gives up after
        ``max_steps`` such changes, when nothing moves any more, or past ``horizon`` [s].
        """
        act = active
        for _ in range(max_steps):
            flow = self.flow_of(act, values)
            if not flow.moving:
                return None
            dt = self.next_change(values, flow, self._watch(flow, cond_comps))
            if dt is None:
                return None
            t_next = grid_after(t + dt, self.config.grid)
            if t_next > horizon:
                return None
            facts, values, act = self.advance(t, facts, values, t_next, log, act)
            t = t_next
            if cond(facts, values):
                return self._with_margin(t, facts, values, cond, cond_comps, log, act, margin)
        return None

    def _watch(self, flow: Flow, cond_comps: frozenset[int]) -> tuple[int, ...]:
        moving = flow.coeffs
        own = [c for c in cond_comps if self.ct.comps.items[c].fluents & moving.keys()]
        return tuple(sorted(set(own) | set(self.comps_for(flow, "dynamic"))))

    def _with_margin(
        self, t: float, facts: int, values: Values, cond: CondFn, cond_comps: frozenset[int],
        log: EventLog, active: tuple[int, ...], margin: float,
    ) -> tuple[float, int, Values, tuple[int, ...]]:
        if margin <= 0.0:
            return t, facts, values, active
        flow = self.flow_of(active, values)
        if not flow.moving:
            return t, facts, values, active
        dt = self.next_change(values, flow, self._watch(flow, cond_comps), 2.0 * margin)
        step = margin if dt is None else min(margin, 0.5 * dt)
        until = round(math.floor((t + step) / self.config.grid) * self.config.grid, 9)
        if until <= t:
            return t, facts, values, active
        trial: EventLog = []
        f2, v2, a2 = self.advance(t, facts, values, until, trial, active)
        if not cond(f2, v2):
            return t, facts, values, active
        log.extend(trial)
        return until, f2, v2, a2


Buckets = dict[int, list[int]]


class LinearRows:
    """Comparisons ``a * v_f + b op 0`` solved together: earliest root along a flow of degree
    <= 2 (closed form, vectorised)."""

    def __init__(self, ids: list[int], f: np.ndarray, a: np.ndarray, b: np.ndarray) -> None:
        self.ids, self.f, self.a, self.b = ids, f, a, b

    @classmethod
    def of(cls, ids: list[int], items: list) -> LinearRows:
        fs, as_, bs = [], [], []
        for c in ids:
            coeffs, const = items[c].linear
            (f, a), = coeffs.items()
            fs.append(f)
            as_.append(a)
            bs.append(const)
        return cls(ids, np.array(fs, dtype=np.intp), np.array(as_), np.array(bs))

    def first_root(self, values: Values, flow: Flow, n: int, horizon: float) -> float | None:
        dense = flow.dense(n)
        v = np.asarray(values)
        p0 = self.a * v[self.f] + self.b
        p1 = self.a * dense[0, self.f]
        with np.errstate(divide="ignore", invalid="ignore"):
            if flow.degree <= 1:
                roots = -p0 / p1
            else:
                p2 = self.a * dense[1, self.f]
                disc = p1 * p1 - 4.0 * p2 * p0
                touch = (disc < 0.0) & (disc > -1e-12 * np.maximum(1.0, p1 * p1))
                disc = np.where(touch, 0.0, disc)
                sq = np.sqrt(disc)
                q = -0.5 * (p1 + np.copysign(sq, p1))
                r1 = np.where(p2 != 0.0, q / p2, -p0 / p1)
                r2 = np.where(p2 != 0.0, p0 / q, np.inf)
                roots = np.concatenate((r1, r2))
            ok = roots[(roots > DT_MIN) & (roots <= horizon)]
        return float(ok.min()) if ok.size else None


@dataclass(frozen=True)
class _ClassHead:
    index: int
    req: int


def _buckets(ops: list) -> tuple[list[tuple[int, list[int]]], list[int]]:
    """Index operators by one required fact, so only those whose key fact holds are checked."""
    buckets: Buckets = {}
    always: list[int] = []
    for op in ops:
        if op.req:
            key = (op.req & -op.req).bit_length() - 1
            buckets.setdefault(key, []).append(op.index)
        else:
            always.append(op.index)
    return [(1 << k, v) for k, v in sorted(buckets.items())], always


def _candidates(
    facts: int, buckets: list[tuple[int, list[int]]], always: list[int]
) -> list[int]:
    out = list(always)
    for bit, ids in buckets:
        if facts & bit:
            out.extend(ids)
    return out
