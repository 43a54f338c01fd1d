"""What holds just after a time point: the reference semantics' rules, fast.

This mirrors :func:`artiplan.semantics.settled_flow` and the boundary rule of
:func:`artiplan.semantics.fire_events` (the validator's), so the search predicts what the validator
will compute:

- a comparison is *near* its boundary when ``|left - right| <= zero_tol``; its truth just after
  now is decided by the sign of the first non-vanishing coefficient of ``left - right`` along the
  flow (exact, no look-ahead step);
- processes: start from those whose precondition holds now (exact up to ``zero_tol``); the ones
  with a comparison near its boundary that reads a changing fluent are re-decided on the right
  limit of the resulting flow, repeatedly, at most ``max_rounds`` times;
- events: one fires if its precondition holds now (VAL's slack) or, near a boundary, on the right
  limit.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from artiplan.pddl.task import And, Atom, Comparison, Condition, Not, Or, Truth
from artiplan.search.compiled import CompiledTask
from artiplan.search.flow import Flow, comparison_poly

ZERO_TOL = 1e-9  # semantics.FlowConfig.zero_tol
MAX_ROUNDS = 8  # semantics.settled_flow's max_rounds


class RightLimit:
    """Right-limit truth of process and event preconditions over a compiled task."""

    def __init__(self, ct: CompiledTask) -> None:
        self.ct = ct
        self._cid: dict[int, int] = {}
        self.proc_reads = [self._reads(p.pre_comps) for p in ct.processes]
        self.event_reads = [self._reads(e.pre_comps) for e in ct.events]
        for cond in [p.precondition for p in ct.task.processes] + [
            e.precondition for e in ct.task.events
        ]:
            self._index(cond)
        items = ct.comps.items
        single = [c for c, it in enumerate(items)
                  if it.linear is not None and len(it.linear[0]) == 1]
        self._single = np.array(single, dtype=np.intp)
        self._f = np.array([next(iter(items[c].linear[0])) for c in single],  # type: ignore[index]
                           dtype=np.intp)
        self._a = np.array([next(iter(items[c].linear[0].values())) for c in single])  # type: ignore[index]
        self._b = np.array([items[c].linear[1] for c in single])  # type: ignore[index]
        self._other = [c for c in range(len(items)) if c not in set(single)]
        self.procs_of: dict[int, list[int]] = {}
        for p in ct.processes:
            for c in p.pre_comps:
                self.procs_of.setdefault(c, []).append(p.index)
        self.events_of: dict[int, list[int]] = {}
        for e in ct.events:
            for c in e.pre_comps:
                self.events_of.setdefault(c, []).append(e.index)
        self._last: tuple[tuple[float, ...], frozenset[int]] | None = None

    def _reads(self, comps: frozenset[int]) -> frozenset[int]:
        out: set[int] = set()
        for c in comps:
            out |= self.ct.comps.items[c].fluents
        return frozenset(out)

    def _index(self, cond: Condition) -> None:
        if isinstance(cond, Comparison):
            self._cid[id(cond)] = self.ct.comps.add(cond)
        elif isinstance(cond, Not):
            self._index(cond.operand)
        elif isinstance(cond, (And, Or)):
            for part in cond.parts:
                self._index(part)

    # ------------------------------------------------------------------ comparisons
    def near_comps(self, values: tuple[float, ...]) -> frozenset[int]:
        """Every comparison within ``ZERO_TOL`` of its boundary (vectorised; memoised)."""
        if self._last is not None and self._last[0] is values:
            return self._last[1]
        out: set[int] = set()
        if self._single.size:
            d = self._a * np.asarray(values)[self._f] + self._b
            out.update(int(c) for c in self._single[np.abs(d) <= ZERO_TOL])
        for c in self._other:
            if self.near(frozenset((c,)), values):
                out.add(c)
        found = frozenset(out)
        self._last = (values, found)
        return found

    def near(self, comps: frozenset[int], values: tuple[float, ...]) -> bool:
        """True if one of ``comps`` is within ``ZERO_TOL`` of its boundary."""
        items = self.ct.comps.items
        for c in comps:
            lin = items[c].linear
            if lin is not None:
                d = lin[1] + sum(a * values[j] for j, a in lin[0].items())
            else:
                poly = comparison_poly(items[c], values, Flow({}))
                d = poly[0] if poly is not None else 1.0
            if abs(d) <= ZERO_TOL:
                return True
        return False

    def _sign_after(self, cid: int, values: tuple[float, ...], flow: Flow) -> int:
        poly = comparison_poly(self.ct.comps.items[cid], values, flow)
        if poly is None:
            return 0
        if abs(poly[0]) > ZERO_TOL:
            return 1 if poly[0] > 0 else -1
        for c in poly[1:]:
            if c != 0.0:
                return 1 if c > 0 else -1
        return 0

    def holds_after(
        self, cond: Condition, facts: int, values: tuple[float, ...], flow: Flow
    ) -> bool:
        """Truth of ``cond`` on (0, eps) along ``flow``."""
        def comp(c: Comparison) -> bool:
            sign = self._sign_after(self._cid[id(c)], values, flow)
            return {">": sign > 0, ">=": sign >= 0, "<": sign < 0, "<=": sign <= 0}.get(
                c.op, sign == 0)

        return _truth(cond, facts, comp)

    # ------------------------------------------------------------------ processes
    def settle_active(
        self, facts: int, values: tuple[float, ...],
        point: tuple[int, ...], flow_of: Callable[[tuple[int, ...]], Flow],
        changing: Callable[[tuple[int, ...]], frozenset[int]],
    ) -> tuple[int, ...]:
        """The active processes just after now (``semantics.settled_flow``'s fixpoint)."""
        near = self.near_comps(values)
        if not near:
            return point
        procs = self.ct.processes
        edge = sorted({p for c in near for p in self.procs_of.get(c, ())
                       if not facts & procs[p].forb and not procs[p].req & ~facts})
        if not edge:
            return point
        active = point
        point_set = set(point)
        for _ in range(MAX_ROUNDS):
            flow = flow_of(active)
            if not flow.moving and not active:
                return active
            moving = changing(active)
            by_class: dict[int, bool] = {}
            decided = {}
            for p in edge:
                if self.proc_reads[p] & moving:
                    cls = self.ct.processes[p].pre_class
                    if cls not in by_class:
                        by_class[cls] = self.holds_after(
                            self.ct.task.processes[p].precondition, facts, values, flow)
                    decided[p] = by_class[cls]
            nxt = tuple(sorted(
                (point_set - set(decided)) | {p for p, ok in decided.items() if ok}))
            if nxt == active:
                return active
            active = nxt
        return active


def _truth(cond: Condition, facts: int, comp: Callable[[Comparison], bool]) -> bool:
    if isinstance(cond, Atom):
        return bool(facts >> cond.fact & 1)
    if isinstance(cond, Comparison):
        return comp(cond)
    if isinstance(cond, And):
        return all(_truth(p, facts, comp) for p in cond.parts)
    if isinstance(cond, Or):
        return any(_truth(p, facts, comp) for p in cond.parts)
    if isinstance(cond, Not):
        return not _truth(cond.operand, facts, comp)
    assert isinstance(cond, Truth)
    return cond.value
