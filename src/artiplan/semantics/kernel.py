"""The PDDL+ kernel: instants and the passing of time over a compiled task, for the validator
and the planner alike.

Rules (VAL's, measured where VAL is unclear: benchmarks/results/semantics.md):

- **Happenings.** The actions of one happening are applied in parallel (every condition and
  right-hand side read in the state before it; deletes before adds). Events of that instant
  fire before the actions; the events the actions trigger fire after them.
- **Events** fire at the earliest time their precondition holds: at a time point read with
  the task's tolerances, or, on a boundary (``|p| <= tol.zero``), on the *right limit* along
  the flow (exact: the sign of the first non-vanishing Taylor coefficient). They cascade to a
  fixpoint; an event triggered twice at one time point is an error (:class:`EventError`).
- **Processes** run while their precondition holds. Which ones run just after a time point is
  decided on the right limit: start from those that hold at the point (snapped), re-decide the
  ones with a comparison on its boundary that reads a changing fluent under the resulting
  flow, until the set is stable. The set is recomputed only at events and actions.
- **Time** passes exactly: to the earliest root of a changing event or process precondition
  (polynomial roots, or the numeric flow's bracketed crossings).

Facts as a bit mask, values as a tuple. Counters (``events``, ``boundary_flows``,
``numeric_flows``) feed the planner's statistics.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Condition, GroundAction, Task
from artiplan.records import dataclass, field
from artiplan.semantics import polynomial as P
from artiplan.semantics.compiled import UPDATE, Comparison, CompiledTask, Operator
from artiplan.semantics.flow import DT_MIN, STILL, Flow, NumericFlow, Shape, make_flow, shape_of
from artiplan.semantics.walks import evaluate, truth

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from typing import Any

Values = tuple[float, ...]
#: The running processes' indices, ascending.
Active = tuple[int, ...]
#: ``(time [s], event index)`` in firing order.
EventLog = list[tuple[float, int]]


def latest_event(log: EventLog, quiet: frozenset[int], default: float = -math.inf) -> float:
    """Time [s] of the latest event in ``log`` that is not in ``quiet`` (re-arms, which an
    action may come close to), or ``default``."""
    for t, i in reversed(log):
        if i not in quiet:
            return t
    return default


class EventError(InvalidPlanError):
    """An event triggered twice at one time point (VAL: "Attempt to trigger event twice")."""

    def __init__(self, event: GroundAction, time: float) -> None:
        self.event, self.time = event, time
        super().__init__(
            f"event {event.signature} triggered twice at time {time:.6f}: its effect does not "
            "falsify its precondition (or a cascade re-triggers it)")


class ZenoError(InvalidPlanError):
    """Events keep firing, or critical instants keep coming, without time passing."""


class InvariantError(InvalidPlanError):
    """An invariant (a global constraint, an ``over all`` condition) fails as time passes."""

    def __init__(self, condition: Condition, time: float, task: Task) -> None:
        from artiplan.semantics.walks import format_condition

        self.condition, self.time = condition, time
        super().__init__(f"invariant {format_condition(condition, task)} fails at time "
                         f"{time:.6f}")


@dataclass(frozen=True)
class Segment:
    """The flow that holds on [t0, t1] [s], from the values ``start`` at t0."""

    t0: float
    t1: float
    start: Values
    flow: Flow

    def values_at(self, t: float) -> Values:
        return self.flow.values(self.start, t - self.t0)


@dataclass
class Kernel:
    """The kernel over one compiled task, with its caches and counters."""

    ct: CompiledTask
    max_cascade: int = 200
    counters: dict[str, int] = field(
        default_factory=lambda: {"events": 0, "boundary_flows": 0, "numeric_flows": 0})

    def __post_init__(self) -> None:
        ct = self.ct
        members: dict[int, list[int]] = {}
        for proc in ct.processes:
            members.setdefault(proc.pre_class, []).append(proc.index)
        self._class_members = [members[c] for c in range(len(members))]
        heads = [ct.processes[m[0]] for m in self._class_members]
        self._class_buckets, self._class_always = _buckets(
            [(c, h.req) for c, h in enumerate(heads)])
        self._event_buckets, self._event_always = _buckets([(e.index, e.req) for e in ct.events])
        self._const_rates = [all(lin is not None and not lin[0] for *_, lin in p.rates)
                             for p in ct.processes]
        self._flows: dict[tuple[int, ...], Flow] = {}
        self._shapes: dict[tuple[int, ...], Shape] = {}
        # flows from start values, most recent last (a search asks for one node's flow again
        # for each of its waits, popped at different times): at most FLOW_CACHE of them
        self._recent: dict[tuple[tuple[int, ...], Values], Flow] = {}
        self._comp_cache: dict[tuple[frozenset[int], str, int | None], tuple[int, ...]] = {}
        self._split_cache: dict[tuple[int, ...], tuple[_Rows | None, tuple[int, ...]]] = {}
        items = ct.comps.items
        self._singles = _Rows.of([c for c, it in enumerate(items) if it.single is not None],
                                 items)
        self._other = [c for c, it in enumerate(items) if it.single is None]
        # per comparison, the processes and the events whose preconditions read it
        self._procs_of: dict[int, list[int]] = {}
        self._events_of: dict[int, list[int]] = {}
        for readers_of, ops in ((self._procs_of, ct.processes), (self._events_of, ct.events)):
            for op in ops:
                for c in op.pre_comps:
                    readers_of.setdefault(c, []).append(op.index)
        self._event_reads = [frozenset().union(*(items[c].fluents for c in e.pre_comps))
                             for e in ct.events]
        # The fact literals (required, forbidden) of whatever reads each dynamic comparison; a
        # comparison no enabled reader has cannot change the dynamics until facts change,
        # which happens only at a happening (a guarded wrap, a flag event that fired).
        readers: dict[int, set[tuple[int, int]]] = {}
        lits = [(e.pre_comps, e.req, e.forb) for e in ct.events]
        lits += [(p.pre_comps, p.req, p.forb) for p in ct.processes]
        for comps, req, forb in lits:
            for c in comps:
                readers.setdefault(c, set()).add((req, forb))
        for _, used in ct.invariants:
            for c in used:
                readers.setdefault(c, set()).add((0, 0))
        self._readers = {c: tuple(r) for c, r in readers.items()}
        self._reader_mask = 0
        for rs in self._readers.values():
            for req, forb in rs:
                self._reader_mask |= req | forb
        self._comp_ids: dict[int, int] = {}
        self._near_memo: tuple[Values, frozenset[int]] | None = None

    # ----------------------------------------------------------------------- processes, flows
    def active(self, facts: int, values: Values) -> tuple[int, ...]:
        """The processes whose (snapped) precondition holds at a time point."""
        procs = self.ct.processes
        out: list[int] = []
        for cls in _candidates(facts, self._class_buckets, self._class_always):
            members = self._class_members[cls]
            head = procs[members[0]]
            if not facts & head.forb and head.pre(facts, values):
                out.extend(members)
        out.sort()
        return tuple(out)

    def shape(self, active: tuple[int, ...]) -> Shape:
        found = self._shapes.get(active)
        if found is None:
            found = self._shapes[active] = shape_of(self.ct.processes, active)
        return found

    #: Flows from start values kept for a later call with the same values (a flow is a
    #: function of its processes and start values: a cached one answers as a new one would).
    FLOW_CACHE = 64

    def flow_of(self, active: tuple[int, ...], values: Values) -> Flow:
        """The flow while exactly ``active`` run, from ``values`` (cached for constant rates,
        and the last :attr:`FLOW_CACHE` others)."""
        if not active:
            return STILL
        cached = self._flows.get(active)
        if cached is not None:
            return cached
        key = (active, values)
        recent = self._recent.get(key)
        if recent is not None:
            return recent
        flow = make_flow(self.shape(active), values, self.ct.tol)
        if isinstance(flow, NumericFlow):
            self.counters["numeric_flows"] += 1
        elif all(self._const_rates[i] for i in active):
            self._flows[active] = flow
            return flow
        if len(self._recent) >= self.FLOW_CACHE:
            del self._recent[next(iter(self._recent))]
        self._recent[key] = flow
        return flow

    def flow(self, facts: int, values: Values) -> tuple[tuple[int, ...], Flow]:
        """The processes running just after a time point, and their flow (right limit)."""
        point = self.active(facts, values)
        settled = self._settle_active(facts, values, point)
        if settled != point:
            self.counters["boundary_flows"] += 1
        return settled, self.flow_of(settled, values)

    # ------------------------------------------------------------------------- right limits
    def near_comps(self, values: Values) -> frozenset[int]:
        """Every comparison within ``tol.zero`` of its boundary (vectorised; memoised)."""
        if self._near_memo is not None and self._near_memo[0] is values:
            return self._near_memo[1]
        zero = self.ct.tol.zero
        out = set(self._singles.near(values, zero))
        for c in self._other:
            try:
                if abs(evaluate(self.ct.comps.items[c].expr, values)) <= zero:
                    out.add(c)
            except ZeroDivisionError:
                continue
        found = frozenset(out)
        self._near_memo = (values, found)
        return found

    def sign_after(self, cid: int, values: Values, flow: Flow, dt: float = 0.0) -> int:
        """Sign of comparison ``cid``'s ``p`` just after ``dt`` along ``flow`` (0: stays 0)."""
        comp = self.ct.comps.items[cid]
        if isinstance(flow, NumericFlow):
            return flow.sign_after(comp, dt)
        poly = flow.poly(comp, values)
        if poly is None:
            return 0
        if dt:
            poly = P.shift(poly, dt)
        return P.sign_after(poly, self.ct.tol.zero)

    def holds_after(self, cond: Condition, facts: int, values: Values, flow: Flow) -> bool:
        """Truth of ``cond`` on (0, eps) along ``flow``."""
        comps = self.ct.comps

        def comparison(c: object) -> bool:
            key = id(c)
            cid = self._comp_ids.get(key)
            if cid is None:
                cid = self._comp_ids[key] = comps.add(c)  # type: ignore[arg-type]
            sign = self.sign_after(cid, values, flow)
            op = c.op  # type: ignore[attr-defined]
            return {">": sign > 0, ">=": sign >= 0, "<": sign < 0, "<=": sign <= 0}.get(
                op, sign == 0)

        return truth(cond, facts, comparison)

    def _settle_active(self, facts: int, values: Values, point: Active) -> Active:
        near = self.near_comps(values)
        if not near:
            return point
        procs = self.ct.processes
        edge = sorted({p for c in near for p in self._procs_of.get(c, ())
                       if not facts & procs[p].forb and not procs[p].req & ~facts})
        if not edge:
            return point
        active, point_set = point, set(point)
        for _ in range(8):
            flow = self.flow_of(active, values)
            moving = self.shape(active).changing
            by_class: dict[int, bool] = {}
            decided: dict[int, bool] = {}
            for p in edge:
                if procs[p].reads & moving:
                    cls = procs[p].pre_class
                    if cls not in by_class:
                        by_class[cls] = self.holds_after(
                            self.ct.task.processes[p].precondition, facts, values, flow)
                    decided[p] = by_class[cls]
            nxt = tuple(sorted((point_set - set(decided)) | {p for p, ok in decided.items() if ok}))
            if nxt == active:
                break
            active = nxt
        return active

    def check_invariants(self, t: float, facts: int, values: Values, flow: Flow) -> None:
        """Raise :class:`InvariantError` if an invariant fails on the stretch of time that
        starts at ``t`` [s] (its truth just after ``t``, the right limit, along ``flow``)."""
        near = self.near_comps(values)
        for k, (fn, comps) in enumerate(self.ct.invariants):
            cond = self.ct.task.invariants[k]
            ok = fn(facts, values)
            if comps & near or not ok:
                ok = self.holds_after(cond, facts, values, flow)
            if not ok:
                raise InvariantError(cond, t, self.ct.task)

    # ------------------------------------------------------------------------------ instants
    def settle(self, t: float, facts: int, values: Values, log: EventLog
               ) -> tuple[int, Values, Active]:
        """Fire every event triggered at time ``t`` [s], cascading to a fixpoint (facts set by
        active processes applied too). Returns the facts, values and the processes running
        just after ``t``. Raises :class:`EventError` or :class:`ZenoError`."""
        events = self.ct.events
        procs = self.ct.processes
        fired: set[int] = set()
        for _ in range(self.max_cascade):
            act, flow = self.flow(facts, values)
            quirk_add = quirk_del = 0
            for p in act:
                quirk_add |= procs[p].adds
                quirk_del |= procs[p].deletes
            new = (facts & ~quirk_del) | quirk_add
            if new != facts:
                facts = new
                continue
            near = self.near_comps(values)
            edge = {e for c in near for e in self._events_of.get(c, ())} if near else set()
            changing = flow.changing if edge else frozenset()
            triggered = []
            for i in _candidates(facts, self._event_buckets, self._event_always):
                ev = events[i]
                if facts & ev.forb:
                    continue
                try:
                    now = ev.pre(facts, values)
                except ZeroDivisionError:
                    now = False
                if now or (i in edge and self._event_reads[i] & changing and self.holds_after(
                        ev.source.precondition, facts, values, flow)):
                    triggered.append(i)
            if not triggered:
                return facts, values, act
            for i in triggered:
                if i in fired:
                    raise EventError(events[i].source, t)
            facts, values = self.apply([events[i] for i in sorted(triggered)], facts, values)
            for i in sorted(triggered):
                fired.add(i)
                log.append((t, i))
                self.counters["events"] += 1
        raise ZenoError(f"events keep firing at t={t:.6f}: the task has an event loop")

    @staticmethod
    def apply(ops: Sequence[Operator], facts: int, values: Values) -> tuple[int, Values]:
        """The state after ``ops`` applied in parallel (one of them: its fast function)."""
        if len(ops) == 1:
            return ops[0].effect(facts, values)
        add = dele = 0
        updates: list[tuple[int, str, float]] = []
        for op in ops:
            a, d, u = op.parts(facts, values)
            add, dele = add | a, dele | d
            updates += u
        if not updates:
            return (facts & ~dele) | add, values
        out = list(values)
        for i, kind, rhs in updates:
            out[i] = UPDATE[kind](out[i], rhs)
        return (facts & ~dele) | add, tuple(out)

    # ------------------------------------------------------------------------ passing time
    def comps_for(self, flow: Flow, kind: str, facts: int | None = None) -> tuple[int, ...]:
        """Comparisons of ``kind`` (``watched``, ``dynamic`` or ``spaced``: dynamic, not only a
        re-arm's) that read a changing fluent; with ``facts``, only the dynamic ones that an
        event or process enabled by those facts reads."""
        live = None if facts is None or kind == "watched" else facts & self._reader_mask
        key = (flow.changing, kind, live)
        found = self._comp_cache.get(key)
        if found is None:
            pool = {"watched": self.ct.watched, "dynamic": self.ct.dynamic,
                    "spaced": self.ct.spaced}[kind]
            ids: set[int] = set()
            for f in flow.changing:
                ids.update(c for c in self.ct.fluent_comps.get(f, ()) if c in pool)
            if live is not None:
                ids = {c for c in ids if any(live & req == req and not live & forb
                                             for req, forb in self._readers.get(c, ((0, 0),)))}
            found = tuple(sorted(ids))
            if len(self._comp_cache) < 200_000:
                self._comp_cache[key] = found
        return found

    def next_change(self, values: Values, flow: Flow, comps: tuple[int, ...],
                    horizon: float = math.inf) -> float | None:
        """Earliest dt > 0 [s] (<= ``horizon``) at which one of ``comps`` may change truth."""
        if not comps:
            return None
        if isinstance(flow, NumericFlow):
            items = self.ct.comps.items
            return flow.crossing([items[c] for c in comps], horizon)
        rows, general = self._split(comps)
        best, found = horizon, False
        if rows is not None:
            if flow.degree <= 2:
                r = rows.first_root(values, flow, best)
                if r is not None:
                    best, found = r, True
            else:
                general = tuple(rows.ids) + general
        items = self.ct.comps.items
        for cid in general:
            poly = flow.poly(items[cid], values)
            if poly is None:
                continue
            roots = P.positive_roots(poly, best, self.ct.tol.zero)
            roots = [r for r in roots if r > DT_MIN]
            if roots:
                best, found = roots[0], True
        return best if found else None

    def _split(self, comps: tuple[int, ...]) -> tuple[_Rows | None, tuple[int, ...]]:
        found = self._split_cache.get(comps)
        if found is None:
            items = self.ct.comps.items
            single = [c for c in comps if items[c].single is not None]
            rest = tuple(c for c in comps if items[c].single is None)
            found = (_Rows.of(single, items) if single else None, rest)
            if len(self._split_cache) < 100_000:
                self._split_cache[comps] = found
        return found

    def advance(
        self, t: float, facts: int, values: Values, until: float, log: EventLog,
        active: Active, segments: list[Segment] | None = None,
    ) -> tuple[int, Values, Active]:
        """Let time pass from ``t`` to ``until`` [s] with ``active`` running from ``t``.

        Events fire at their exact times (the active processes are recomputed there); at
        ``until`` itself only if it is such a time. ``segments`` (if given) receives the flow
        of every stretch.
        """
        act = active
        for _ in range(1_000_000):
            if until - t <= 0.0:
                return facts, values, act
            flow = self.flow_of(act, values)
            if self.ct.invariants:
                self.check_invariants(t, facts, values, flow)
            if not flow.moving:
                if segments is not None:
                    segments.append(Segment(t, until, values, flow))
                return facts, values, act
            dt = self.next_change(values, flow, self.comps_for(flow, "dynamic", facts), until - t)
            if dt is None or t + dt >= until:
                if segments is not None:
                    segments.append(Segment(t, until, values, flow))
                values = flow.values(values, until - t)
                if dt is not None and t + dt >= until - 1e-12:  # critical exactly at until
                    facts, values, act = self.settle(until, facts, values, log)
                return facts, values, act
            if segments is not None:
                segments.append(Segment(t, t + dt, values, flow))
            values = flow.values(values, dt)
            t += dt
            facts, values, act = self.settle(t, facts, values, log)
        raise ZenoError(f"time cannot pass beyond t={t:.6f}")


class _Rows:
    """Comparisons ``a * v_f + b op 0``, handled together: which are on their boundary, and
    the earliest root along a flow of degree <= 2 (closed form). Pure Python; vectorised
    with numpy (imported only then) for large sets."""

    #: From this many comparisons on, numpy is used.
    VECTOR = 96

    def __init__(self, ids: list[int], rows: list[tuple[int, float, float]]) -> None:
        self.ids, self.rows = ids, rows
        self._np: tuple[Any, ...] | None = None

    @classmethod
    def of(cls, ids: list[int], items: list[Comparison]) -> _Rows:
        rows = [items[c].single for c in ids]
        return cls(ids, [r for r in rows if r is not None])

    def _arrays(self) -> tuple[Any, ...]:
        if self._np is None:
            import numpy as np

            f, a, b = zip(*self.rows, strict=True) if self.rows else ((), (), ())
            self._np = (np, np.array(self.ids, dtype=np.intp), np.array(f, dtype=np.intp),
                        np.array(a), np.array(b))
        return self._np

    def near(self, values: Values, zero: float) -> list[int]:
        """The comparisons with ``|a v_f + b| <= zero``."""
        if len(self.rows) < self.VECTOR:
            return [c for c, (f, a, b) in zip(self.ids, self.rows, strict=True)
                    if abs(a * values[f] + b) <= zero]
        np, ids, f, a, b = self._arrays()
        d = a * np.asarray(values)[f] + b
        return [int(c) for c in ids[np.abs(d) <= zero]]

    def first_root(self, values: Values, flow: Flow, horizon: float) -> float | None:
        """Earliest root in (DT_MIN, horizon] [s] of any of the comparisons along ``flow``."""
        if len(self.rows) >= self.VECTOR:
            return self._first_root_np(values, flow, horizon)
        coeffs = flow.coeffs
        best = math.inf
        for f, a, b in self.rows:
            cs = coeffs.get(f)
            if cs is None:
                continue
            p0, p1 = a * values[f] + b, a * cs[0]
            if len(cs) == 1:  # linear: _quadratic_roots's first case, without the call
                if p1 != 0.0:
                    r = -p0 / p1
                    if DT_MIN < r < best:
                        best = r
                continue
            for r in _quadratic_roots(p0, p1, a * cs[1]):
                if DT_MIN < r < best:
                    best = r
        return best if best <= horizon and best != math.inf else None

    def _first_root_np(self, values: Values, flow: Flow, horizon: float) -> float | None:
        np, _, f, a, b = self._arrays()
        n = len(values)
        c1, c2 = np.zeros(n), np.zeros(n)
        for i, cs in flow.coeffs.items():
            c1[i] = cs[0]
            if len(cs) > 1:
                c2[i] = cs[1]
        p0 = a * np.asarray(values)[f] + b
        p1, p2 = a * c1[f], a * c2[f]
        with np.errstate(divide="ignore", invalid="ignore"):
            disc = p1 * p1 - 4.0 * p2 * p0
            touch = (disc < 0.0) & (disc > -1e-12 * np.maximum(1.0, p1 * p1))
            sq = np.sqrt(np.where(touch, 0.0, disc))
            q = -0.5 * (p1 + np.copysign(sq, p1))
            r1 = np.where(p2 != 0.0, q / p2, -p0 / p1)
            r2 = np.where(p2 != 0.0, p0 / q, np.inf)
            roots = np.concatenate((r1, r2))
            ok = roots[(roots > DT_MIN) & (roots <= horizon)]
        return float(ok.min()) if ok.size else None


def _quadratic_roots(p0: float, p1: float, p2: float) -> tuple[float, ...]:
    """Real roots of ``p2 t^2 + p1 t + p0`` (stable form; a touching root lost to rounding
    kept; none for a constant)."""
    if p2 == 0.0:
        return (-p0 / p1,) if p1 != 0.0 else ()
    disc = p1 * p1 - 4.0 * p2 * p0
    if disc < 0.0:
        if disc <= -1e-12 * max(1.0, p1 * p1):
            return ()
        disc = 0.0
    q = -0.5 * (p1 + math.copysign(math.sqrt(disc), p1))
    return (q / p2, p0 / q) if q != 0.0 else (q / p2,)


Buckets = tuple[int, dict[int, list[int]]]


def _buckets(ops: list[tuple[int, int]]) -> tuple[Buckets, list[int]]:
    """Index (operator, required mask) by one required fact (its lowest), so only those whose
    key fact holds are checked: (mask of the key facts, key bit -> operators), and the
    operators that require no fact."""
    buckets: dict[int, list[int]] = {}
    always: list[int] = []
    for index, req in ops:
        if req:
            buckets.setdefault(req & -req, []).append(index)
        else:
            always.append(index)
    return (sum(buckets), buckets), always  # distinct single bits: their sum is their union


def _candidates(facts: int, buckets: Buckets, always: list[int]) -> list[int]:
    """The operators whose key fact holds in ``facts``, and those without one; walks the set
    key bits only (a state holds few of the many guard and flag facts)."""
    out = list(always)
    mask, by_bit = buckets
    live = facts & mask
    while live:
        bit = live & -live
        out.extend(by_bit[bit])
        live ^= bit
    return out
