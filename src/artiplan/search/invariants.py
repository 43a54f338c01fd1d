"""Threatened invariants: when the running processes will break one, and which actions save it.

An invariant (an ENHSP global constraint, a durative action's ``over all``) only prunes in the
kernel: a wait that would break it stops at the last grid time before. That is too late to act
in two steps (free a shared resource, then start the process that saves the invariant), since
the second action comes ``epsilon`` after the first and an action is refused when a condition
flips within ``event_gap`` after it. And nothing tells the search *which* action saves it, so a
long run of switches (a thermostat keeping rooms in their bands for minutes) is searched as a
tree of every action at every stop.

This module gives the search, for a state:

- the earliest time [s] a holding invariant comparison fails along the current flow, and the
  comparisons that fail then (the *threat*);
- the *rescues*: actions applicable now after which that comparison no longer fails that soon
  (they change the flow of its fluents), and the *enablers*: applicable actions after which a
  rescue that is not applicable now becomes applicable (releasing a capacity it needs).

The search waits until ``lead`` seconds before a threat (:class:`~artiplan.search.engine.
WaitRescue`) and prefers the rescues and enablers there. Nothing is keyed on names: only the
task's invariants, its actions' effects and the processes they start or stop.
"""

from __future__ import annotations

import math

from artiplan.search.waits import comparison_holds, floor_grid
from artiplan.semantics.compiled import CompiledTask, Operator
from artiplan.semantics.kernel import Kernel, Values


class Threats:
    """Invariant threats and their rescues over one kernel (only for tasks with invariants)."""

    def __init__(self, ct: CompiledTask, kernel: Kernel, lead: float) -> None:
        self.ct, self.kernel, self.lead = ct, kernel, lead
        self.comps = tuple(sorted(frozenset().union(*(used for _, used in ct.invariants))))

    def first(self, values: Values, active: tuple[int, ...]) -> tuple[float, tuple[int, ...]]:
        """(dt [s], comparisons) of the earliest failure of a holding invariant comparison
        along the flow of ``active`` (``inf``, () if none fails)."""
        k = self.kernel
        flow = k.flow_of(active, values)
        if not flow.moving:
            return math.inf, ()
        items = k.ct.comps.items
        best, which = math.inf, []
        for c in self.comps:
            if not items[c].fluents & flow.changing or \
                    not comparison_holds(self.ct, c, values, snapped=False):
                continue
            dt = k.next_change(values, flow, (c,))
            if dt is None or not math.isfinite(dt):
                continue
            if dt < best - 1e-9:
                best, which = dt, [c]
            elif dt <= best + 1e-9:
                which.append(c)
        return best, tuple(which)

    def advice(self, t: float, facts: int, values: Values, active: tuple[int, ...],
               rescue: bool = True) -> tuple[float, list[int], bool]:
        """What the search should offer at a state at ``t`` [s]: (seconds to wait, to
        ``lead`` before the next threat; 0 if none or closer), the rescues and enablers when
        the threat is that close already and ``rescue`` (the search's call: not after an
        action that made the threat itself, a pour started into an empty tank, whose rescue
        would only undo it), and whether the threat is that close."""
        dt, comps = self.first(values, active)
        if not comps:
            return 0.0, [], False
        if dt <= 2.0 * self.lead:
            return 0.0, self.rescues(facts, values, comps, dt) if rescue else [], True
        grid = self.ct.tol.grid
        end = floor_grid(t + dt - self.lead, grid)
        return (round(end - t, 9) if end > t + grid else 0.0), [], False

    def _saves(self, act: Operator, facts: int, values: Values, comps: tuple[int, ...],
               dt: float) -> bool:
        """True when applying ``act`` (its effect only) leaves no comparison of ``comps``
        failing within ``dt + lead`` [s], and no invariant comparison failing within two
        leads (a pour started from a nearly empty tank saves the generator's fuel only to
        threaten the tank's at once)."""
        f2, v2 = act.effect(facts, values)
        active = self.kernel.active(f2, v2)
        flow = self.kernel.flow_of(active, v2)
        items = self.ct.comps.items
        for c in comps:
            if not items[c].fluents & flow.changing:
                continue
            dt2 = self.kernel.next_change(v2, flow, (c,))
            if dt2 is not None and dt2 <= dt + self.lead:
                return False
        return self.first(v2, active)[0] > 2.0 * self.lead

    def rescues(self, facts: int, values: Values, comps: tuple[int, ...],
                dt: float) -> list[int]:
        """Applicable actions that save ``comps`` (failing in ``dt`` [s]), then the enablers
        of rescues not applicable now; each once, in action order."""
        if not comps:
            return []
        saving: list[int] = []
        blocked: list[Operator] = []
        for a in self.ct.actions:
            if a.noop or facts & a.forb or not self._saves(a, facts, values, comps, dt):
                continue
            if not a.req & ~facts and a.pre(facts, values):
                saving.append(a.index)
            else:
                blocked.append(a)
        if not blocked:
            return saving
        found = set(saving)
        for a in self.ct.actions:
            if a.index in found or a.noop or facts & a.forb or a.req & ~facts \
                    or not a.pre(facts, values):
                continue
            f2, v2 = a.effect(facts, values)
            if any(not b.req & ~f2 and not f2 & b.forb and b.pre(f2, v2) for b in blocked):
                saving.append(a.index)
                found.add(a.index)
        return saving


__all__ = ["Threats"]
