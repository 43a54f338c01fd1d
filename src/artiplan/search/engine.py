"""Greedy best-first search in exact time, with lazy evaluation and preferred operators.

A node is a state at a time on the plan grid. Its successors (operators) are:

- :class:`Apply` ``(i)``: apply action ``i`` now, or ``epsilon`` after the previous action if
  that was less than ``epsilon`` ago (VAL applies same-time actions in parallel), and
  ``event_gap`` after the last event; then cascade events;
- :class:`WaitNext`: wait until the next critical time (a watched comparison may flip);
- :class:`WaitGroup` ``(g)``: wait until goal group ``g`` holds, plus a margin while it holds;
- :class:`WaitGoal`: wait until the whole goal holds.

Evaluation is lazy (as in Fast Downward's lazy search): successors enter the open lists with
their parent's value and are computed when popped. Two open lists, all operators and preferred
ones, are popped alternately, with a boost for the preferred list after progress (LAMA). Ties are
broken by insertion order, so a run is deterministic. Duplicates are detected on the facts and the
values rounded to ``value_precision``. One pruning: an action applied right after another (no
wait between) that restores the facts from before that other action, and every number the two
write unless they only set it to a constant, is skipped (a start then stop that only lets
``epsilon`` pass; two increases in a row are kept).
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable

from artiplan.errors import InvalidPlanError
from artiplan.pddl.task import Atom
from artiplan.records import dataclass, field, replace
from artiplan.search.heuristic import Evaluation, Heuristic
from artiplan.search.invariants import Threats
from artiplan.search.ops import (
    START,
    WAIT_BEFORE,
    WAIT_DELTA,
    WAIT_GOAL,
    WAIT_NEXT,
    Apply,
    Op,
    Rescue,
    WaitBefore,
    WaitDelta,
    WaitFor,
    WaitGroup,
    WaitHold,
    WaitNext,
)
from artiplan.search.waits import Waits, ceil_grid, grid_after
from artiplan.semantics.compiled import CompiledTask, Operator
from artiplan.semantics.kernel import EventLog, Kernel, Values, latest_event
from artiplan.semantics.walks import conjuncts
from artiplan.tolerances import VAL_EVENT_WINDOW


@dataclass(frozen=True)
class SearchConfig:
    """Settings of the search.

    Attributes:
        epsilon: Separation [s] between successive actions (> VAL's tolerance 0.001).
        value_precision: Values are rounded to this many decimals for duplicate detection.
        goal_margin: Extra time [s] a goal wait runs on, while the goal (group) keeps holding,
            so the plan's last happening sees the goal with a margin.
        margin_per_event: The goal margin grows by this [s] per event on the path, up to
            ``max_goal_margin`` [s]: stock VAL fires an event anywhere in its 0.01 s window
            around a happening, and on long cascades (30 links, 350 events) the shifts add up
            to a few tenths of a degree (benchmarks/results/semantics.md, class 4).
        boost: Pops from the preferred list after each improvement of the best value.
        max_wait_steps: Critical times one macro wait may cross.
        event_gap: No action closer than this [s] to an event, before or after it (VAL fires
            an event due within its event window after a happening at that happening, and
            then loses the processes the action starts: benchmarks/results/semantics.md).
            An action due sooner after an event waits; one that an event would follow too
            soon is not applied. 0 turns the rule off.
        delta: Step [s] of the free waits (:class:`WaitDelta`); None: waits stop only where
            a condition may change, or just before.
        before_events: :class:`WaitBefore` also stops ``event_gap`` before the next event
            (the last moment to act before a tank runs dry).
        g_weight: Open-list priority is ``h + g_weight * actions on the path`` (0: greedy).
        max_repairs: Timing repairs (``repair`` callback) one search may try at most.
    """

    epsilon: float = 0.001
    value_precision: int = 6
    goal_margin: float = 0.01
    margin_per_event: float = 0.0002
    max_goal_margin: float = 0.1
    boost: int = 1000
    max_wait_steps: int = 64
    event_gap: float = 1.5 * VAL_EVENT_WINDOW
    delta: float | None = None
    before_events: bool = False
    g_weight: float = 0.0
    max_repairs: int = 25


@dataclass
class Node:
    """A search node: the state at ``time`` [s] and how it was reached."""

    time: float
    facts: int
    values: Values
    ready: float  # earliest time of the next action [s]
    parent: int
    op: Op
    events: EventLog
    by_action: bool
    active: tuple[int, ...] = ()  # processes running from ``time`` on
    after: int = 0  # events[after:] were triggered by the node's action
    n_actions: int = 0  # actions on the path from the initial node
    last_event: float = -math.inf  # time of the latest event on the path [s]
    forced: int = 0  # rescues among the actions on the path (not counted in g)
    n_events: int = 0  # events on the path from the initial node
    at_threat: bool = False  # an invariant fails within 2 leads (set when expanded)
    path: int = -1  # the path from the initial node (0) to here, as a Successors key; -1: none


@dataclass
class SearchOutcome:
    """What the search loop found: the goal node (or None) and its counters."""

    goal: int | None
    nodes: list[Node]
    closing: tuple[float, int] | None  # (time, no-op action) that ends the plan, if any
    stats: dict[str, float] = field(default_factory=dict)
    exhausted: bool = False
    repaired: bool = False  # a timing repair of a path gave the plan (the accept callback has it)


#: Successors already computed, shared by searches over one task and one configuration: (the
#: parent's ``Node.path``, the operator's class, the operator) -> the child (None: inapplicable).
#: A successor depends only on the path that leads to its parent (the parent's state, and for an
#: action the state before the parent's action), so searches from the same initial node that
#: meet the same path compute it once.
Successors = dict[tuple[int, type, Op], "Node | None"]
#: A memo stops growing at this many successors (a long first search would otherwise keep an
#: entry per node it generated); a child left out has no path id, so neither have its own.
MEMO_LIMIT = 200_000


class Search:
    """One search over a compiled task."""

    def __init__(
        self, ct: CompiledTask, kernel: Kernel, heuristic: Heuristic, config: SearchConfig,
        check_limits: Callable[[], None],
        accept: Callable[[SearchOutcome], bool] = lambda outcome: True,
        prune: Callable[[Node], bool] | None = None,
        repair: Callable[[list[int], list[float]], bool] | None = None,
        successors: Successors | None = None,
    ) -> None:
        """``successors``: a memo of successors shared with other searches of the same task,
        kernel and ``config`` from the same initial node (and heuristics with the same goal
        groups); not with ``repair``, whose side effects a memo would skip."""
        assert successors is None or repair is None, "a memo would skip the repairs"
        self.ct, self.kernel, self.h, self.config = ct, kernel, heuristic, config
        self.memo = successors
        # invariants the running processes threaten: wait to just before, then the rescues
        lead = 2.0 * config.event_gap + 2.0 * config.epsilon
        self.threats = Threats(ct, kernel, lead) if ct.invariants else None
        self.waits = Waits(kernel, lead if ct.invariants else 0.0)
        self.check_limits, self.accept = check_limits, accept
        self.prune = prune  # nodes it returns True for are dropped (the improvement's bound)
        # repair(actions, times) -> True when it made them a valid plan (timing repair)
        self.repair = repair
        goal_facts = {c.fact for c in conjuncts(ct.task.goal) if isinstance(c, Atom)}
        self.achievers = [a.index for a in ct.actions
                          if goal_facts & set(ct.task.actions[a.index].effect.add)]
        self.tried: dict[tuple[float, ...], int] = {}  # skeletons repaired (actions, times)
        self.repaired = False
        self.noops = [a.index for a in ct.actions if a.noop]
        # the operators, built once (heap entries hold them)
        self.applies = [Apply(a.index) for a in ct.actions]
        self.action_waits = [WaitFor(a.index) for a in ct.actions]
        # comparisons that may close a window to act: action preconditions and invariants
        self.closers = frozenset().union(*(a.pre_comps for a in ct.actions),
                                         *(used for _, used in ct.invariants))
        # comparisons whose change fires an event: acting just before one is a choice too
        self.triggers: frozenset[int] = frozenset().union(
            *(e.pre_comps for e in ct.events if e.index not in ct.rearms)
        ) if config.before_events else frozenset()
        self.group_waits = [WaitGroup(g) for g in range(len(heuristic.groups))]
        self.nodes: list[Node] = []
        self.seen: set[tuple[int, tuple[int, ...], tuple[float | None, ...]]] = set()
        self.counter = itertools.count()
        self.stats: dict[str, float] = dict.fromkeys(
            ("expanded", "generated", "evaluated", "duplicates", "undo_pruned", "invalid",
             "rejected", "pruned", "gap_pruned", "repairs", "repaired", "reused"), 0)

    # ------------------------------------------------------------------ successors
    def _key(self, node: Node) -> tuple[int, tuple[int, ...], tuple[float | None, ...]]:
        prec = self.config.value_precision
        values = tuple(None if v != v else round(v, prec) for v in node.values)
        return node.facts & ~self.ct.guards, node.active, values

    def successor(self, parent: Node, pi: int, op: Op) -> Node | None:
        """The node ``op`` leads to from ``parent`` (index ``pi``), or None if inapplicable."""
        memo = self.memo if parent.path >= 0 else None
        if memo is not None:
            key = (parent.path, type(op), op)
            if key in memo:
                self.stats["reused"] += 1
                known = memo[key]
                return None if known is None else replace(known, parent=pi, at_threat=False)
        try:
            child = self._successor(parent, pi, op)
        except InvalidPlanError:  # an event loop or an event triggered twice: no happening
            self.stats["invalid"] += 1
            child = None
        if memo is not None and len(memo) < MEMO_LIMIT:
            if child is not None:
                child.path = len(memo) + 1
            memo[key] = child
        return child

    def _successor(self, parent: Node, pi: int, op: Op) -> Node | None:
        log: EventLog = []
        kernel = self.kernel
        if isinstance(op, Apply):
            at = self._happening(parent, log)
            if at is None:
                return None
            t, facts, values, _ = at
            act = self.ct.actions[op.action]
            if facts & act.forb or not act.pre(facts, values):
                return None
            facts, values = act.effect(facts, values)
            after = len(log)
            facts, values, active = kernel.settle(t, facts, values, log)
            if parent.by_action and isinstance(parent.op, Apply) and \
                    self._undoes(parent, act, facts, values):
                # undoes the previous action after only epsilon: pointless
                self.stats["undo_pruned"] += 1
                return None
            if self._event_follows(t, values, active):
                return None
            ready = round(t + self.config.epsilon, 9)
            return Node(t, facts, values, ready, pi, op, log, True, active, after,
                        parent.n_actions + 1, last_event_after(parent, log, self.ct.rearms),
                        parent.forced + isinstance(op, Rescue),
                        n_events=parent.n_events + len(log))
        if isinstance(op, WaitNext):
            res = self.waits.next(parent.time, parent.facts, parent.values, log, parent.active,
                                  self.goal_margin(parent), self.ct.goal_comps)
        elif isinstance(op, WaitBefore):
            res = self.waits.before(parent.time, parent.facts, parent.values, log,
                                    parent.active, self.closers, self.triggers,
                                    self.config.event_gap)
        elif isinstance(op, WaitDelta):
            assert self.config.delta is not None
            res = self.waits.delta(parent.time, parent.facts, parent.values, log,
                                   parent.active, self.config.delta)
        elif isinstance(op, WaitHold):
            res = self.waits.hold(parent.time, parent.facts, parent.values, log,
                                  parent.active, op.seconds)
        elif isinstance(op, WaitFor):
            act = self.ct.actions[op.action]
            res = self.waits.until(parent.time, parent.facts, parent.values, act.pre,
                                   act.pre_comps, log, parent.active, self.config.max_wait_steps)
            if res is None and self.repair is not None and op.action in self.achievers:
                self._repair(parent, pi, op.action)
        else:
            if isinstance(op, WaitGroup):
                g = self.h.groups[op.group]
                fn, comps = g.fn, g.comps
            else:
                fn, comps = self.ct.goal, self.ct.goal_comps
            res = self.waits.until(parent.time, parent.facts, parent.values, fn, comps, log,
                                   parent.active, self.config.max_wait_steps,
                                   self.goal_margin(parent))
        if res is None:
            return None
        t, facts, values, active = res
        return Node(t, facts, values, parent.ready, pi, op, log, False, active,
                    n_actions=parent.n_actions,
                    last_event=last_event_after(parent, log, self.ct.rearms), forced=parent.forced,
                    n_events=parent.n_events + len(log))

    def goal_margin(self, node: Node) -> float:
        """The goal margin [s] of a goal wait from ``node``: the base margin, grown with the
        events on the path (``SearchConfig.margin_per_event``)."""
        c = self.config
        return min(c.max_goal_margin, c.goal_margin + c.margin_per_event * node.n_events)

    def _undoes(self, parent: Node, act: Operator, facts: int, values: Values) -> bool:
        """True when ``act`` right after ``parent``'s action restores the facts from before
        it, and every number the two write is restored or only set to a constant (a start then
        stop: held-index back to 1; two increases in a row are kept)."""
        before = self.nodes[parent.parent]
        if facts != before.facts:
            return False
        assert isinstance(parent.op, Apply)
        prev = self.ct.actions[parent.op.action]
        written = (act.writes - act.resets) | (prev.writes - prev.resets)
        return all(values[i] == before.values[i] for i in written)

    def _happening(
        self, node: Node, log: EventLog
    ) -> tuple[float, int, Values, tuple[int, ...]] | None:
        """The earliest time [s] at which an action may follow ``node`` (``epsilon`` after the
        previous action, ``event_gap`` after every event), with the settled state and active
        processes there; the events on the way are appended to ``log``. None if events keep
        coming closer than ``event_gap``."""
        kernel, gap, grid = self.kernel, self.config.event_gap, self.waits.grid
        t0, facts, values, active = node.time, node.facts, node.values, node.active
        t = max(node.time, node.ready)
        if node.last_event + gap > t:
            t = ceil_grid(node.last_event + gap, grid)
        for _ in range(16):
            facts, values, _ = kernel.advance(t0, facts, values, t, log, active)
            # a happening: events of that instant first, then the action (the validator's order)
            facts, values, active = kernel.settle(t, facts, values, log)
            latest = latest_event(log, self.ct.rearms)
            if latest <= t - gap + 1e-9:
                return t, facts, values, active
            t0, t = t, ceil_grid(latest + gap, grid)
        return None

    def _event_follows(self, t: float, values: Values, active: tuple[int, ...]) -> bool:
        """True when an event (or a process switch) would follow a happening at ``t`` within
        ``event_gap`` (counted as ``gap_pruned``)."""
        gap = self.config.event_gap
        if gap <= 0.0:
            return False
        flow = self.kernel.flow_of(active, values)
        if not flow.moving:
            return False
        dt = self.kernel.next_change(values, flow, self.kernel.comps_for(flow, "spaced"), gap)
        if dt is None:
            return False
        self.stats["gap_pruned"] += 1
        return True

    def closing(self, node: Node) -> tuple[float, int] | None | bool:
        """How a goal node ends the plan: True if its action does, (time, no-op) or None.

        The no-op keeps ``event_gap`` from every event, as actions do; the goal must hold
        there."""
        if (node.by_action or node.parent < 0) and node.last_event <= node.time - \
                self.config.event_gap:
            return True
        trial: EventLog = []
        try:
            at = self._happening(node, trial)
        except InvalidPlanError:
            return None
        if at is None:
            return None
        t, facts, values, active = at
        if not self.ct.goal(facts, values):
            return None
        if self._event_follows(t, values, active):
            return None
        for i in self.noops:
            if self.ct.actions[i].pre(facts, values):
                return t, i
        return None

    # ------------------------------------------------------------------ the loop
    def run(self, initial: Node, max_expansions: float = float("inf")) -> SearchOutcome:
        """Lazy GBFS with a preferred-operator list; returns when the goal or the end is found,
        or (``goal`` None, ``exhausted`` False) after ``max_expansions`` expansions."""
        regular: list[tuple[float, int, int, Op]] = []
        preferred: list[tuple[float, int, int, Op]] = []
        boost = 0
        best_h = float("inf")
        pop_preferred = True
        pending: list[tuple[int, Op]] = [(-1, START)]
        while True:
            self.check_limits()
            if self.stats["expanded"] >= max_expansions:
                return SearchOutcome(None, self.nodes, None, self.stats, exhausted=False)
            if pending:
                pi, op = pending.pop()
            else:
                use_pref = preferred and (boost > 0 or pop_preferred or not regular)
                queue = preferred if use_pref else regular
                if not queue:
                    return SearchOutcome(None, self.nodes, None, self.stats, exhausted=True)
                _, _, pi, op = heapq.heappop(queue)
                if use_pref and boost > 0:
                    boost -= 1
                pop_preferred = not pop_preferred
            node = initial if pi < 0 else self.successor(self.nodes[pi], pi, op)
            if self.repaired:
                return SearchOutcome(None, self.nodes, None, self.stats, repaired=True)
            if node is None:
                continue
            if self.prune is not None and self.prune(node):
                self.stats["pruned"] += 1
                continue
            key = self._key(node)
            if key in self.seen:
                self.stats["duplicates"] += 1
                continue
            self.seen.add(key)
            self.nodes.append(node)
            ni = len(self.nodes) - 1
            if self.ct.goal(node.facts, node.values):
                end = self.closing(node)
                if end is not None:
                    found = SearchOutcome(ni, self.nodes, None if end is True else end,  # type: ignore[arg-type]
                                          self.stats)
                    if self.accept(found):
                        return found
                    self.stats["rejected"] += 1
            active = node.active
            ev = self.h.evaluate(node.facts, node.values, active)
            self.stats["evaluated"] += 1
            self.stats["expanded"] += 1
            if ev.h < best_h:
                best_h = ev.h
                boost += self.config.boost
            prio = ev.h + self.config.g_weight * (node.n_actions - node.forced)
            moving = self.kernel.flow_of(active, node.values).moving
            for op2, pref in self._operators(node, ev, moving):
                entry = (prio, next(self.counter), ni, op2)
                heapq.heappush(regular, entry)
                if pref:
                    heapq.heappush(preferred, entry)
                self.stats["generated"] += 1

    def _repair(self, parent: Node, pi: int, a: int) -> None:
        """Try a timing repair of the path to ``parent`` ended by goal achiever ``a``, whose
        numbers the running processes bring close but miss (its wait found no time). The
        achiever goes where its comparisons next change (the closest approach, typically);
        each skeleton (actions and times) is tried once, ``max_repairs`` in all."""
        assert self.repair is not None
        if self.stats["repairs"] >= self.config.max_repairs:
            return
        actions, times = self.path_actions(pi)
        key = (*actions, a, *(round(t, 3) for t in times))
        if key in self.tried:
            return  # the same skeleton from another node of the path: the same repair
        self.tried[key] = 1
        flow = self.kernel.flow_of(parent.active, parent.values)
        items = self.ct.comps.items
        comps = tuple(sorted(c for c in self.ct.actions[a].pre_comps
                             if items[c].fluents & flow.changing))
        dt = self.kernel.next_change(parent.values, flow, comps) if comps else None
        at = parent.time + (dt if dt is not None and math.isfinite(dt) else 0.0)
        at = max(at, parent.ready, parent.last_event + self.config.event_gap)
        self.stats["repairs"] += 1
        if self.repair([*actions, a], [*times, at]):
            self.stats["repaired"] += 1
            self.repaired = True

    def path_actions(self, ni: int) -> tuple[list[int], list[float]]:
        """The actions on the path to node ``ni`` and their times [s], in order."""
        actions: list[int] = []
        times: list[float] = []
        while ni >= 0:
            node = self.nodes[ni]
            if isinstance(node.op, Apply):
                actions.append(node.op.action)
                times.append(node.time)
            ni = node.parent
        return actions[::-1], times[::-1]

    def _operators(self, node: Node, ev: Evaluation, moving: bool) -> list[tuple[Op, bool]]:
        """Operators of a node, preferred first (their order breaks ties)."""
        ops: list[tuple[Op, bool]] = []
        if moving:
            if ev.hold > 0.0:  # the heuristic's motion keeps the controls this long
                ops.append((WaitHold(ev.hold), True))
            if not ev.actions_needed and ev.unsatisfied:
                ops.append((WAIT_GOAL, True))
            ops.extend((self.group_waits[gi], True) for gi in ev.waits)
        pref = set(ev.preferred)
        if self.threats is not None and moving:
            # rescues after a wait, or continuing a rescue (an enabler, then the rescue)
            rescue = not node.by_action or self.nodes[node.parent].at_threat
            seconds, saving, node.at_threat = self.threats.advice(
                node.time, node.facts, node.values, node.active, rescue)
            ops.extend((Rescue(i), True) for i in saving)
            if seconds > 0.0:
                ops.append((WaitHold(seconds), True))
            pref.update(saving)
        for i in ev.preferred:
            if i in pref and self.threats is not None and (Rescue(i), True) in ops:
                continue
            act = self.ct.actions[i]
            if moving and act.pre_comps and not act.pre(node.facts, node.values):
                ops.append((self.action_waits[i], True))  # its numbers are not there yet
            else:
                ops.append((self.applies[i], True))
        if moving:
            ops.append((WAIT_NEXT, False))
            if self.triggers or (self.closers and self.waits.closing(node.values, node.active,
                                                                      self.closers)):
                ops.append((WAIT_BEFORE, False))
            if self.config.delta is not None:
                ops.append((WAIT_DELTA, False))
        for a in self.ct.actions:
            if a.index in pref or a.noop or node.facts & a.forb or a.req & ~node.facts:
                continue
            ops.append((self.applies[a.index], False))
        return ops


def initial_node(ct: CompiledTask, kernel: Kernel) -> Node:
    """The initial state after the events it triggers at time 0."""
    log: EventLog = []
    facts, values, active = kernel.settle(0.0, ct.init_facts, ct.init_values, log)
    return Node(0.0, facts, values, 0.0, -1, START, log, False, active,
                last_event=latest_event(log, ct.rearms), n_events=len(log), path=0)


def last_event_after(parent: Node, log: EventLog, quiet: frozenset[int] = frozenset()) -> float:
    """The latest event time on the path through ``parent`` and then ``log`` [s], re-arms
    (``quiet``) left out."""
    return max(parent.last_event, latest_event(log, quiet))


__all__ = ["Node", "Search", "SearchConfig", "SearchOutcome", "grid_after", "initial_node",
           "last_event_after"]
