"""A heuristic that knows rates: numeric relaxation with processes as achievers.

For every goal conjunct that reads one fluent ``x`` (``x > 150``; a window across the wrap), the
cheapest way to satisfy it is one process that moves ``x``: the cost is what it takes to switch
that process on (``hadd`` over the facts of its precondition, 0 if it already runs) plus
``time_weight`` times the time it needs, ``travel / |rate|``. ``travel`` follows the fluent in
the process's direction, through the jumps of wrap-around events, to the goal set. A process that
already runs and moves several goal fluents (the propagation of one rotation) costs no action for
any of them, which is how one action that moves several angles is rewarded. Fact goals cost their
``hadd`` value, other conjuncts 1.

Preferred operators (helpful actions): the applicable actions that start the chosen processes
(following ``hadd`` supporters back to an applicable one), and the waits for conjuncts whose
chosen process already runs.
"""

from __future__ import annotations

import heapq
import math
import time
from collections.abc import Callable, Sequence

from artiplan.pddl.task import And, Atom, Condition, Effect, Not
from artiplan.records import dataclass
from artiplan.search.intervals import (
    Intervals,
    Jump,
    condition_set,
    intersect,
    travel,
)
from artiplan.search.sideeffects import SideEffects
from artiplan.semantics.compiled import ComparisonTable, CompiledTask, CondFn, compile_condition
from artiplan.semantics.walks import Linear, conjuncts, linear


def _unguarded(cond: Condition, guards: int) -> Condition | None:
    """``cond`` without its guard literals (``not g`` for a guard fact in the mask ``guards``,
    :func:`~artiplan.semantics.compiled.guard_facts`); ``None`` if it reads another fact.
    Relaxed, a guarded wrap is a plain wrap."""
    parts = [c for c in conjuncts(cond)
             if not (isinstance(c, Not) and isinstance(c.operand, Atom)
                     and guards >> c.operand.fact & 1)]
    if any(isinstance(c, Atom) or isinstance(c, Not) and isinstance(c.operand, Atom)
           for c in parts):
        return None
    return parts[0] if len(parts) == 1 else And(tuple(parts))


@dataclass(frozen=True)
class HeuristicConfig:
    """Weights of the heuristic.

    Attributes:
        time_weight: Cost of one second of waiting, in actions [1/s].
        unreachable_cost: Cost of a conjunct no process seems to reach (kept finite: the
            relaxation is not a proof, the search stays complete).
        damage_cost: Cost of undoing a goal already reached (a stop and a start).
    """

    time_weight: float = 0.1
    unreachable_cost: float = 1000.0
    damage_cost: float = 2.0


@dataclass(frozen=True)
class GoalGroup:
    """Goal conjuncts that read one fluent (``fluent``), one fact literal, or anything else."""

    fn: CondFn
    comps: frozenset[int]
    fluent: int | None = None
    target: Intervals = ()
    literal: int | None = None


TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # at run time a plain class: nothing checks the protocol there


class Heuristic(Protocol):
    """What the search asks of a heuristic (another one plugs in through
    ``PlannerConfig.heuristic``, as in pyperplan): a protocol for type checkers."""

    #: The goal's groups; the search's group waits (``WaitGroup``) refer to them by index.
    groups: list[GoalGroup]
    #: Time spent evaluating [s].
    seconds: float

    def evaluate(self, facts: int, values: tuple[float, ...],
                 active: tuple[int, ...]) -> Evaluation:
        """The value of a state whose running processes are ``active``."""
        ...


@dataclass(frozen=True)
class Evaluation:
    """The value of a state and what the heuristic recommends."""

    h: float
    preferred: tuple[int, ...]  # helpful action indices, widest reach first
    waits: tuple[int, ...]  # goal groups whose chosen process already runs
    actions_needed: bool  # some unsatisfied group needs a new action
    unsatisfied: int
    hold: float = 0.0  # a wait [s] the relaxation asks for before the next action (0: none)


def propagate(heap: list[tuple[float, int]], cost: list[float], users: Sequence[Sequence[int]],
              remaining: list[int], acc: list[float], fire: Callable[[int], None]) -> None:
    """The fixpoint of an additive relaxation: nodes leave ``heap`` cheapest first; an
    operator (an index into ``remaining``/``acc``) fires once its last precondition is reached,
    ``acc`` holding the sum of their costs; ``fire`` pushes what it reaches onto ``heap``."""
    heapq.heapify(heap)
    done = [False] * len(cost)
    while heap:
        c, node = heapq.heappop(heap)
        if done[node] or c > cost[node]:
            continue
        done[node] = True
        for i in users[node]:
            remaining[i] -= 1
            acc[i] += c
            if remaining[i] == 0:
                fire(i)


class RateHeuristic(SideEffects):
    """The rate-aware numeric relaxation over a compiled task."""

    def __init__(
        self, ct: CompiledTask, config: HeuristicConfig | None = None,
        active_fn: Callable[[int, tuple[float, ...]], tuple[int, ...]] | None = None,
    ) -> None:
        """``active_fn(facts, values)``: the processes running in a state (from the search's
        simulator); with it, the side effects of switching a process on are those of the
        actions that switch it on, applied to the current state (gravity included)."""
        self.ct = ct
        self.active_fn = active_fn
        self._after: dict[tuple[int, ...], tuple[tuple[int, tuple[Linear, ...]], ...]] = {}
        self._state: tuple[int, tuple[float, ...], tuple[list[float], list[int]] | None] = (
            0, (), None)
        self.config = config or HeuristicConfig()
        self.damage_cost = self.config.damage_cost
        self.n_facts = len(ct.task.facts)
        self.groups = self._groups()
        self._relaxed_actions()
        self.movers: dict[int, list[tuple[int, Linear]]] = {}
        for p in ct.processes:
            for fluent, _, lin in p.rates:
                if lin is not None:
                    self.movers.setdefault(fluent, []).append((p.index, lin))
        self.proc_lits = [self._lits(p.req, p.forb) for p in ct.processes]
        # actions that change what a process's numeric precondition reads (e.g. the held link)
        self.enablers: list[tuple[int, ...]] = []
        for proc in ct.processes:
            reads = frozenset().union(*(ct.comps.items[c].fluents for c in proc.pre_comps))
            self.enablers.append(tuple(a.index for a in ct.actions if a.writes & reads))
        self.jumps = self._jumps()
        self._side_effects()
        self.seconds = 0.0  # time spent in evaluate() [s]
        self._moves_cache: dict[tuple[int, ...], tuple[tuple[int, tuple[Linear, ...]], ...]] = {}
        # hadd costs by facts (they read neither values nor weights: shared when reweighted)
        self._cost_cache: dict[int, tuple[list[float], list[int]]] = {}
        self._active_set: set[int] = set()
        self._active_moves: tuple[tuple[int, tuple[Linear, ...]], ...] = ()

    def reweighted(self, config: HeuristicConfig) -> RateHeuristic:
        """This heuristic with other weights, without building it again: the setup (goal
        groups, relaxed actions, side effects, jumps) reads the task only and is shared, and
        so is the cache of process motions (by the running processes alone); the state of the
        last evaluation needs no copy (every ``evaluate`` binds it anew)."""
        other = object.__new__(type(self))
        other.__dict__.update(self.__dict__)
        other.config, other.damage_cost, other.seconds = config, config.damage_cost, 0.0
        return other

    # --------------------------------------------------------------------------- setup
    def _lits(self, req: int, forb: int) -> tuple[int, ...]:
        pos = [i for i in range(self.n_facts) if req >> i & 1]
        neg = [self.n_facts + i for i in range(self.n_facts) if forb >> i & 1]
        return tuple(pos + neg)

    def _groups(self) -> list[GoalGroup]:
        by_fluent: dict[int, list[Condition]] = {}
        groups: list[GoalGroup] = []
        comps: ComparisonTable = self.ct.comps
        for conj in conjuncts(self.ct.task.goal):
            fn, used = compile_condition(conj, comps, self.ct.tol, snap=self.ct.strict)
            fls = set().union(*(comps.items[c].fluents for c in used)) if used else set()
            if len(fls) == 1 and condition_set(conj, next(iter(fls))) is not None:
                by_fluent.setdefault(next(iter(fls)), []).append(conj)
            elif isinstance(conj, Atom):
                groups.append(GoalGroup(fn, used, literal=conj.fact))
            elif isinstance(conj, Not) and isinstance(conj.operand, Atom):
                groups.append(GoalGroup(fn, used, literal=self.n_facts + conj.operand.fact))
            else:
                groups.append(GoalGroup(fn, used))
        for fluent in sorted(by_fluent):
            conjs = by_fluent[fluent]
            fn, used = compile_condition(And(tuple(conjs)), comps, self.ct.tol,
                                         snap=self.ct.strict)
            target: Intervals = ((-math.inf, math.inf),)
            for c in conjs:
                s = condition_set(c, fluent)
                assert s is not None
                target = intersect(target, s)
            groups.append(GoalGroup(fn, used, fluent=fluent, target=target))
        return groups

    def _relax(self, req: int, forb: int, eff: Effect) -> None:
        """Enter the next relaxed operator: its precondition's fact literals, and what it adds
        (conditional adds too) and deletes."""
        n = self.n_facts
        adds = set(eff.add) | {f for ce in eff.conditional for f in ce.effect.add}
        self.pre_lits.append(self._lits(req, forb))
        self.eff_lits.append(tuple(sorted(adds)) + tuple(n + f for f in sorted(set(eff.delete))))
        for lit in self.pre_lits[-1]:
            self.lit_users[lit].append(len(self.pre_lits) - 1)

    def _relaxed_actions(self) -> None:
        self.pre_lits: list[tuple[int, ...]] = []
        self.eff_lits: list[tuple[int, ...]] = []
        self.lit_users: list[list[int]] = [[] for _ in range(2 * self.n_facts)]
        for a in self.ct.actions:  # relaxed operator i is action i
            self._relax(a.req, a.forb, self.ct.task.actions[a.index].effect)
        # Events that unblock actions (they delete a fact some action needs false, e.g. the
        # hands' reach timer's ``hands-ready``) are achievers too, free: they fire by
        # themselves once their fact preconditions hold (their clocks are left to the search's
        # own time). Without them every state in which such a fact holds looks dead, and the
        # search avoids ever reaching it (e.g. never releasing the hands).
        blocking = 0
        for a in self.ct.actions:
            blocking |= a.forb
        self.n_actions = len(self.ct.actions)
        #: Relaxed operator index - n_actions -> index of the event in ``ct.events``.
        self.relaxed_events: list[int] = []
        for ev in self.ct.events:
            eff = self.ct.task.events[ev.index].effect
            if any(blocking >> f & 1 for f in eff.delete):
                self.relaxed_events.append(ev.index)
                self._relax(ev.req, ev.forb, eff)

    def _jumps(self) -> dict[int, tuple[Jump, ...]]:
        """Events that read one fluent and shift or set it: wrap-arounds."""
        out: dict[int, list[Jump]] = {}
        for ev in self.ct.task.events:
            eff = ev.effect
            if eff.conditional or len(eff.numeric) != 1:
                continue
            ne = eff.numeric[0]
            numeric = _unguarded(ev.precondition, self.ct.guards)
            trigger = None if numeric is None else condition_set(numeric, ne.fluent)
            lin = linear(ne.expr)
            if trigger is None or lin is None or lin[0]:
                continue
            k = lin[1]
            scale, shift = {
                "assign": (0.0, k), "increase": (1.0, k), "decrease": (1.0, -k),
            }.get(ne.op, (1.0, 0.0))
            out.setdefault(ne.fluent, []).append(Jump(trigger, scale, shift))
        return {f: tuple(j) for f, j in out.items()}

    # --------------------------------------------------------------------------- hadd
    #: Most fact states whose costs are kept (then the cache starts again).
    COST_CACHE = 1024

    def fact_costs(self, facts: int) -> tuple[list[float], list[int]]:
        """``hadd`` cost of every fact literal from ``facts``, and each one's best supporter
        (cached by ``facts``: waits and restarts meet the same facts again; read only)."""
        found = self._cost_cache.get(facts)
        if found is None:
            if len(self._cost_cache) >= self.COST_CACHE:
                self._cost_cache.clear()
            found = self._cost_cache[facts] = self._fact_costs(facts)
        return found

    def _fact_costs(self, facts: int) -> tuple[list[float], list[int]]:
        n = self.n_facts
        cost = [math.inf] * (2 * n)
        supp = [-1] * (2 * n)
        heap: list[tuple[float, int]] = []
        for i in range(n):
            lit = i if facts >> i & 1 else n + i
            cost[lit] = 0.0
            heap.append((0.0, lit))
        remaining = [len(p) for p in self.pre_lits]
        acc = [0.0] * len(self.pre_lits)
        for a, pre in enumerate(self.pre_lits):
            if not pre:
                self._achieve(a, self._op_cost(a), cost, supp, heap)
        def fire(a: int) -> None:
            self._achieve(a, acc[a] + self._op_cost(a), cost, supp, heap)

        propagate(heap, cost, self.lit_users, remaining, acc, fire)
        return cost, supp

    def _op_cost(self, a: int) -> float:
        """Cost of relaxed operator ``a``: 1 for an action, 0 for an unblocking event."""
        return 1.0 if a < self.n_actions else 0.0

    def _achieve(
        self, a: int, ca: float, cost: list[float], supp: list[int], heap: list[tuple[float, int]]
    ) -> None:
        for lit in self.eff_lits[a]:
            if ca < cost[lit]:
                cost[lit] = ca
                supp[lit] = a
                heapq.heappush(heap, (ca, lit))

    # --------------------------------------------------------------------------- evaluate
    def evaluate(
        self, facts: int, values: tuple[float, ...], active: tuple[int, ...]
    ) -> Evaluation:
        """Heuristic value of a state whose running processes are ``active``."""
        t0 = time.perf_counter()
        try:
            return self._evaluate(facts, values, active)
        finally:
            self.seconds += time.perf_counter() - t0

    def _evaluate(
        self, facts: int, values: tuple[float, ...], active: tuple[int, ...]
    ) -> Evaluation:
        cfg = self.config
        active_set = set(active)
        self._active_set = active_set
        self._active_moves = self._moves_of(active)
        self._after = {}
        self._state = (facts, values, None)
        costs: tuple[list[float], list[int]] | None = None
        h = 0.0  # time and damage; the relaxed plan's actions are counted once, at the end
        plan: set[int] = set()
        preferred: set[int] = set()
        waits: list[int] = []
        needed = False
        unsat = 0
        satisfied = [g.fn(facts, values) for g in self.groups]
        for gi, g in enumerate(self.groups):
            if satisfied[gi]:
                continue
            unsat += 1
            needed_here = True
            if costs is None:
                costs = self.fact_costs(facts)
                self._state = (facts, values, costs)
            if g.fluent is None:
                c = costs[0][g.literal] if g.literal is not None else 1.0
                if c == math.inf:
                    h += cfg.unreachable_cost
                elif g.literal is not None:
                    self._relaxed_plan((g.literal,), costs, plan, preferred)
                else:
                    h += c
            else:
                best_p, extra = self._best_mover(g, values, active_set, costs, satisfied)
                if best_p < 0:
                    h += cfg.unreachable_cost
                elif best_p in active_set:
                    h += extra
                    waits.append(gi)
                    needed_here = False
                else:
                    h += extra
                    before = len(plan)
                    self._relaxed_plan(self.proc_lits[best_p], costs, plan, preferred)
                    if len(plan) == before:  # its facts hold: a numeric precondition is false
                        h += 1.0
                        preferred.update(
                            a for a in self.enablers[best_p]
                            if all(costs[0][q] == 0.0 for q in self.pre_lits[a]))
            needed = needed or needed_here
        h += len(plan)
        order = sorted(preferred, key=lambda a: (-self.reach[a], a))
        return Evaluation(h, tuple(order), tuple(waits), needed, unsat)

    def _best_mover(
        self, g: GoalGroup, values: tuple[float, ...], active_set: set[int],
        costs: tuple[list[float], list[int]], satisfied: list[bool],
    ) -> tuple[int, float]:
        """The process that best reaches goal group ``g``, and its time and damage cost."""
        assert g.fluent is not None
        cfg = self.config
        best, best_p, best_extra = math.inf, -1, 0.0
        x = values[g.fluent]
        dist_cache: dict[bool, float] = {}
        for p, (coeffs, const) in self.movers.get(g.fluent, ()):
            r = const + sum(a * values[j] for j, a in coeffs.items())
            if r == 0.0:
                continue
            up = r > 0
            if up not in dist_cache:
                dist_cache[up] = travel(x, 1.0 if up else -1.0, g.target,
                                        self.jumps.get(g.fluent, ()))
            d = dist_cache[up]
            if d == math.inf:
                continue
            if p in active_set:
                e = 0.0
            else:  # at least one happening is needed to switch it on
                e = max(1.0, sum(costs[0][lit] for lit in self.proc_lits[p]))
            extra = cfg.time_weight * d / abs(r)
            if e + extra < best:
                extra += self._damage(p, g.fluent, d / abs(r), values, satisfied)
            if e + extra < best:
                best, best_p, best_extra = e + extra, p, extra
        return best_p, best_extra

    def _relaxed_plan(
        self, lits: tuple[int, ...], costs: tuple[list[float], list[int]], plan: set[int],
        preferred: set[int],
    ) -> None:
        """Add the supporters of ``lits`` (recursively) to ``plan``; applicable ones are helpful."""
        cost, supp = costs
        for lit in lits:
            if cost[lit] == 0.0 or supp[lit] < 0:
                continue
            a = supp[lit]
            if a >= self.n_actions:  # an event: not in the plan, its preconditions are
                self._relaxed_plan(self.pre_lits[a], costs, plan, preferred)
                continue
            if a in plan:
                continue
            plan.add(a)
            if all(cost[q] == 0.0 for q in self.pre_lits[a]):
                preferred.add(a)
            else:
                self._relaxed_plan(self.pre_lits[a], costs, plan, preferred)
