"""A numeric relaxation for any PDDL+ task: ``hadd`` over facts *and* comparisons.

The rate heuristic (:mod:`artiplan.search.heuristic`) knows the paper's encodings: numeric goals
on one fluent each, reached by one process. Other people's domains hide their numbers behind
actions (a car's ``stop`` needs the distance in a window and the speed near 0), chain rates (the
distance moves at the speed, the speed at the acceleration), and reach numbers by repeated
actions or by pouring. This relaxation treats every comparison the task reads as a subgoal next
to the fact literals, and computes additive costs (``hadd``, as ENHSP's default) over:

- **actions**, repeated: an action that moves ``p`` (of ``p op 0``) by ``delta`` in the
  current state is applied ``ceil(need / |delta|)`` times (one application if it assigns);
- **events**: free, when one firing makes the comparison true;
- **processes**, one relaxed operator per process and fluent it moves: they reach ``p`` in
  ``need / |dp/dt|`` seconds, each second costing ``time_weight``. A rate that does not point
  the right way yet (the speed is 0, the distance has to grow) becomes a subgoal of its own, the
  comparison ``rate > 0`` (or ``< 0``): the chain ``d`` <- ``v`` <- ``a`` <- ``accelerate``.

Every change is evaluated in the current state (a relaxation, not a proof: the search stays
complete), except where a position is steered through its speed by a control (a car's
acceleration; :mod:`artiplan.search.secondorder`): times then take the most favourable control
levels, and a conjunction wanting the position in a box with the speed in a band is costed
jointly, by the least motion profile and the control steps it needs by its deadline.
Preferred operators are the applicable actions of the relaxed plan, and the actions whose facts
hold while a running process brings their numbers (the search waits for those); a motion goal
adds the actions that move its control the way it must go first, and a wait (``hold``) for as
long as its profile keeps the controls as they are.
"""

from __future__ import annotations

import heapq
import math
import time
from collections.abc import Callable

from artiplan.pddl.task import (
    Atom,
    BinOp,
    Comparison,
    Condition,
    Const,
    Effect,
    Not,
    NumExpr,
    Truth,
)
from artiplan.records import dataclass
from artiplan.search.heuristic import Evaluation, GoalGroup, HeuristicConfig, propagate
from artiplan.search.motion import MotionGoal
from artiplan.search.secondorder import Corner, SecondOrder, Steering, applicable
from artiplan.semantics.compiled import CompiledTask, compile_condition
from artiplan.semantics.walks import (
    conjuncts,
    expr_source,
    fluents_of,
    linear,
    source_function,
)
from artiplan.typenames import Literal

Values = tuple[float, ...]
PFn = Callable[[Values], float]

#: The comparison an operator reads, with the operator flipped under a negation.
_FLIP = {">": "<=", ">=": "<", "<": ">=", "<=": ">"}
#: Cap on the repetitions of one action (keeps costs finite and comparable).
MAX_REPEATS = 1000


def _compile_expr(expr: NumExpr) -> PFn:
    fn: Callable[[Values], float] = source_function(f"lambda V: {expr_source(expr)}")

    def safe(values: Values) -> float:
        try:
            return float(fn(values))
        except (ZeroDivisionError, OverflowError, ValueError):
            return math.nan

    return safe


@dataclass(frozen=True)
class _Cond:
    """``p op 0`` as a relaxed subgoal."""

    p: PFn
    op: str
    fluents: frozenset[int]
    gradient: dict[int, float] | None  # constant partial derivatives, if linear


@dataclass
class _Op:
    """A relaxed operator: an action, an event or one fluent a process moves (with a sign)."""

    kind: str  # "action" | "event" | "process"
    index: int  # into ct.actions / ct.events / ct.processes
    pre: tuple[int, ...]  # node ids
    lits: tuple[int, ...]  # fact literals it adds
    conds: tuple[int, ...]  # condition indices whose p it may move
    additive: frozenset[int] = frozenset()  # conditions it moves by increase/decrease only
    fluent: int = -1  # process: the fluent, its rate, the direction this operator stands for
    rate: PFn | None = None
    sign: int = 0
    reads: frozenset[int] = frozenset()  # process: the fluents its rate reads
    controls: tuple[int, ...] = ()  # process: controls its rate or the rates it reads read
    motion: tuple[MotionGoal, ...] = ()  # action: the position/speed goals of its precondition


class NumericHeuristic:
    """``hadd`` over fact literals and comparisons (see the module's docstring)."""

    def __init__(self, ct: CompiledTask, config: HeuristicConfig | None = None,
                 active_fn: Callable[[int, Values], tuple[int, ...]] | None = None) -> None:
        self.ct = ct
        self.config = config or HeuristicConfig()
        self.n = n = len(ct.task.facts)
        self.zero = ct.tol.zero
        self.conds: list[_Cond] = []
        self._cond_ids: dict[tuple[str, str], int] = {}
        self.ops: list[_Op] = []
        self.seconds = 0.0
        task = ct.task
        for a in ct.actions:
            self._add_instant("action", a.index, task.actions[a.index].precondition,
                              task.actions[a.index].effect)
        for e in ct.events:
            self._add_instant("event", e.index, task.events[e.index].precondition,
                              task.events[e.index].effect)
        for p in ct.processes:
            parts = self._parts(task.processes[p.index].precondition)
            if parts is None:
                continue
            for fluent, rate, lin in p.rates:
                const = lin is not None and not lin[0]
                for sign in (1, -1):
                    pre = list(parts)
                    if const:
                        assert lin is not None
                        if lin[1] * sign <= 0:
                            continue
                    else:  # the rate's sign is a subgoal
                        op: Literal[">", "<"] = ">" if sign > 0 else "<"
                        pre.append(2 * n + self._cond(Comparison(op, rate, Const(0.0))))
                    self.ops.append(_Op("process", p.index, tuple(pre), (), (), fluent=fluent,
                                        rate=_compile_expr(rate), sign=sign,
                                        reads=fluents_of(rate)))
        self.goal_nodes: list[tuple[int, ...]] = []
        self.groups: list[GoalGroup] = []
        for conj in conjuncts(task.goal):
            fn, used = compile_condition(conj, ct.comps, ct.tol, snap=ct.strict)
            self.groups.append(GoalGroup(fn, used))
            self.goal_nodes.append(self._parts(conj) or ())
        # the second-order terms (search/secondorder.py): controls behind process times,
        # motion goals of actions and goal conjuncts
        self.second = SecondOrder(task, self._flow, active_fn, self.config.time_weight, 2 * n)
        for o in self.ops:
            if o.kind == "process":
                o.controls = self.second.controls_of(o.reads)
            elif o.kind == "action":
                o.motion = self.second.goals(task.actions[o.index].precondition, self._cond)
        self.goal_motion = [self.second.goals(conj, self._cond)
                            for conj in conjuncts(task.goal)]
        # which operators may move which conditions (static: by the fluents they touch)
        readers: dict[int, list[int]] = {}
        for k, c in enumerate(self.conds):
            for f in c.fluents:
                readers.setdefault(f, []).append(k)
        written: set[int] = set()  # the fluents an action or an event writes
        for o in self.ops:
            if o.kind == "process":
                o.conds = tuple(readers.get(o.fluent, ()))
            else:
                eff = (task.actions if o.kind == "action" else task.events)[o.index].effect
                moved, additive = _moved(eff)
                written |= moved
                o.conds = tuple(sorted({k for f in moved for k in readers.get(f, ())}))
                o.additive = frozenset(k for k in o.conds if self.conds[k].fluents & moved
                                       <= additive)
        # conditions on clocks: fluents no action or event writes, moved by constant rates
        # only (a deadline); the time they leave bounds every wait before them
        varying = {f for p in ct.processes for f, _, lin in p.rates
                   if lin is None or lin[0]}
        signs: dict[int, set[float]] = {}  # fluent -> signs of the constant rates moving it
        for p in ct.processes:
            for f, _, lin in p.rates:
                if lin is not None and not lin[0] and lin[1]:
                    signs.setdefault(f, set()).add(math.copysign(1.0, lin[1]))

        def against(c: _Cond) -> bool:
            """Time only makes ``c`` worse: every rate moving its fluents closes it."""
            assert c.gradient is not None
            way = 1 if c.op in (">", ">=") else -1
            return c.op != "=" and all(
                len(signs.get(f, ())) == 1 and next(iter(signs[f])) * g * way < 0.0
                for f, g in c.gradient.items() if g)

        self.deadlines = frozenset(
            k for k, c in enumerate(self.conds)
            if c.fluents and not c.fluents & (written | varying) and c.gradient is not None
            and against(c))
        self.rate_fns: list[list[tuple[int, PFn]]] = [
            [(f, _compile_expr(e)) for f, e, _ in p.rates] for p in ct.processes]
        self.users: list[list[int]] = [[] for _ in range(2 * n + len(self.conds))]
        for i, o in enumerate(self.ops):
            for node in o.pre:
                self.users[node].append(i)

    # ------------------------------------------------------------------------------- setup
    def _add_instant(self, kind: str, index: int, pre: Condition, eff: Effect) -> None:
        parts = self._parts(pre)
        if parts is None:
            return
        adds = set(eff.add) | {f for ce in eff.conditional for f in ce.effect.add}
        dels = set(eff.delete) | {f for ce in eff.conditional for f in ce.effect.delete}
        lits = tuple(sorted(adds)) + tuple(self.n + f for f in sorted(dels))
        self.ops.append(_Op(kind, index, parts, lits, ()))

    def _cond(self, comp: Comparison, negate: bool = False) -> int:
        op = _FLIP.get(comp.op, comp.op) if negate else comp.op
        expr: NumExpr = BinOp("-", comp.left, comp.right)
        key = (op, repr(expr))
        found = self._cond_ids.get(key)
        if found is None:
            lin = linear(expr)
            found = self._cond_ids[key] = len(self.conds)
            self.conds.append(_Cond(_compile_expr(expr), op, fluents_of(expr),
                                    dict(lin[0]) if lin is not None else None))
        return found

    def _parts(self, cond: Condition) -> tuple[int, ...] | None:
        """Node ids of the top-level conjuncts of ``cond`` (None: it never holds). Other parts
        (disjunctions) are left out: relaxed, they cost nothing."""
        out: list[int] = []
        n = self.n
        for c in conjuncts(cond):
            if isinstance(c, Atom):
                out.append(c.fact)
            elif isinstance(c, Not) and isinstance(c.operand, Atom):
                out.append(n + c.operand.fact)
            elif isinstance(c, Comparison):
                out.append(2 * n + self._cond(c))
            elif isinstance(c, Not) and isinstance(c.operand, Comparison) \
                    and c.operand.op != "=":
                out.append(2 * n + self._cond(c.operand, negate=True))
            elif isinstance(c, Truth) and not c.value:
                return None
        return tuple(out)

    # ------------------------------------------------------------------------------ values
    def _need(self, k: int, pv: float) -> tuple[float, int]:
        """How far ``p`` must move, and which way, for condition ``k`` to hold."""
        op = self.conds[k].op
        if op == ">=":
            return -pv, 1
        if op == ">":
            return -pv + self.zero, 1
        if op == "<=":
            return pv, -1
        if op == "<":
            return pv + self.zero, -1
        return abs(pv), -1 if pv > 0 else 1

    def _holds(self, k: int, pv: float) -> bool:
        return pv == pv and self.ct.tol.snapped(self.conds[k].op, pv)

    def _slope(self, k: int, fluent: int, values: Values) -> float:
        """``dp/d(fluent)`` of condition ``k`` at ``values``."""
        c = self.conds[k]
        if c.gradient is not None:
            return c.gradient.get(fluent, 0.0)
        return _partial(c.p, values, fluent)

    # ----------------------------------------------------------------------------- evaluate
    def evaluate(self, facts: int, values: Values, active: tuple[int, ...]) -> Evaluation:
        """The value of a state whose running processes are ``active``."""
        t0 = time.perf_counter()
        try:
            return self._evaluate(facts, values, active)
        finally:
            self.seconds += time.perf_counter() - t0

    def _flow(self, values: Values, active: tuple[int, ...]) -> dict[int, float]:
        """d(fluent)/dt of every changing fluent while ``active`` run, at ``values``."""
        out: dict[int, float] = {}
        for p in active:
            for fluent, fn in self.rate_fns[p]:
                out[fluent] = out.get(fluent, 0.0) + fn(values)
        return out

    def _rate_change(self, o: _Op, values: Values, flow: dict[int, float]) -> float:
        """d/dt of operator ``o``'s rate along the current flow (its second order)."""
        rate, total = o.rate, 0.0
        assert rate is not None
        for j in o.reads:
            if flow.get(j):  # (a plain loop: sum() may round differently)
                total += _partial(rate, values, j) * flow[j]
        return total

    def _evaluate(self, facts: int, values: Values, active: tuple[int, ...]) -> Evaluation:
        n, ct, tw = self.n, self.ct, self.config.time_weight
        base = 2 * n
        pv = [c.p(values) for c in self.conds]
        cost = [math.inf] * (base + len(self.conds))
        need_t = [0.0] * len(cost)  # time [s] the cheapest way to a node takes, at least
        supp = [-1] * len(cost)
        for i in range(n):
            cost[i if facts >> i & 1 else n + i] = 0.0
        flow = self._flow(values, active)
        left: dict[int, float] = {}  # deadline conditions: time [s] until they fail
        for k in range(len(self.conds)):
            if self._holds(k, pv[k]):
                cost[base + k] = 0.0
                if k in self.deadlines:
                    left[k] = self._time_left(k, pv[k], values, flow)
        after: dict[int, Values | None] = {}  # action/event index -> values after it, here

        def moved_by(o: _Op, k: int) -> tuple[float, float] | None:
            """(cost beyond the operator's preconditions, time [s]) of reaching condition
            ``k`` by ``o``; None if ``o`` does not reach it."""
            need, way = self._need(k, pv[k])
            if need != need and o.kind == "process":  # undefined here (a quotient by 0)
                return None
            if o.kind == "process":
                assert o.rate is not None
                slope = self._slope(k, o.fluent, values)
                if slope * o.sign * way <= 0.0:
                    return None
                t = self._process_time(o, need, slope, values, flow)
                # the time label: at the most favourable levels of the controls (an action
                # may yet raise the acceleration), so a deadline prunes only what is lost
                best = self._best_time(o, need, slope, values, active, corners) \
                    if o.controls else None
                if t is None:  # the rate turns the right way only later
                    return 1.0, best or 0.0
                return tw * t, t if best is None else min(t, best)
            key = o.index if o.kind == "action" else -1 - o.index
            if key not in after:
                src = ct.actions[o.index] if o.kind == "action" else ct.events[o.index]
                try:
                    after[key] = src.effect(facts, values)[1]
                except (ZeroDivisionError, OverflowError, ValueError):
                    after[key] = None
            w = after[key]
            if w is None:
                return None
            moved = self.conds[k].p(w)
            if self._holds(k, moved):
                return (1.0 if o.kind == "action" else 0.0), 0.0
            delta = moved - pv[k]
            if need != need or o.kind != "action" or k not in o.additive or not delta * way > 0.0 \
                    or not math.isfinite(delta):  # NaN/inf: a quotient by 0 on the way
                return None
            return float(min(MAX_REPEATS, math.ceil(need / abs(delta) - 1e-9))), 0.0

        corners: dict[tuple[int, ...], list[Corner]] = {}
        steer: dict[int, Steering] = {}  # op -> how its motion goals steer the controls
        remaining = [len(o.pre) for o in self.ops]
        acc = [0.0] * len(self.ops)
        heap: list[tuple[float, int]] = [(0.0, i) for i, c in enumerate(cost) if c == 0.0]

        def fire(i: int) -> None:
            o = self.ops[i]
            c0 = acc[i]
            t0 = max((need_t[q] for q in o.pre), default=0.0)
            if o.motion:
                joint = self.second.joint(o.motion, o.pre, facts, values, active, cost, left,
                                          steer.setdefault(i, Steering()))
                if joint is None:
                    return
                c0, t0 = c0 + joint[0], max(t0, joint[1])
            if left and t0 > 0.0:
                # a deadline among its preconditions passes before the others can hold
                for q in o.pre:
                    if q - base in left and left[q - base] < t0:
                        return
            step = 1.0 if o.kind == "action" else 0.0
            for lit in o.lits:
                if c0 + step < cost[lit]:
                    cost[lit], supp[lit], need_t[lit] = c0 + step, i, t0
                    heapq.heappush(heap, (c0 + step, lit))
            for k in o.conds:
                node = base + k
                if cost[node] <= c0:
                    continue
                found = moved_by(o, k)
                if found is not None and c0 + found[0] < cost[node]:
                    cost[node], supp[node], need_t[node] = c0 + found[0], i, t0 + found[1]
                    heapq.heappush(heap, (c0 + found[0], node))

        for i, o in enumerate(self.ops):
            if not o.pre:
                fire(i)
        propagate(heap, cost, self.users, remaining, acc, fire)
        return self._result(cost, supp, acc, active, facts, values, need_t, left, steer)

    def _process_time(self, o: _Op, need: float, slope: float, values: Values,
                      flow: dict[int, float]) -> float | None:
        """Time [s] process operator ``o`` takes to move a condition of slope ``slope`` by
        ``need`` at ``values`` (rate and its change along ``flow``); None: not that way."""
        assert o.rate is not None
        r = abs(slope) * o.rate(values) * o.sign
        r2 = abs(slope) * self._rate_change(o, values, flow) * o.sign
        t = _time_to(need, r, r2) if math.isfinite(r + r2) else None
        return None if t is None or t != t else t

    def _best_time(self, o: _Op, need: float, slope: float, values: Values,
                   active: tuple[int, ...], cache: dict[tuple[int, ...], list[Corner]]
                   ) -> float | None:
        """The least time [s] of ``o`` with its controls at either end of their levels."""
        times = [t for v, f in self.second.corners(o.controls, values, active, cache)
                 if (t := self._process_time(o, need, slope, v, f)) is not None]
        return min(times, default=None)

    def _time_left(self, k: int, pv: float, values: Values, flow: dict[int, float]) -> float:
        """Time [s] until deadline condition ``k`` (it holds now) fails along the flow."""
        rate = sum(self._slope(k, f, values) * r for f, r in flow.items()
                   if f in self.conds[k].fluents)
        _, way = self._need(k, pv)
        closing = -rate * way  # the margin shrinks at this rate
        if closing <= 0.0:
            return math.inf
        return abs(pv) / closing

    def _result(self, cost: list[float], supp: list[int], acc: list[float],
                active: tuple[int, ...], facts: int, values: Values, need_t: list[float],
                left: dict[int, float], steer: dict[int, Steering]) -> Evaluation:
        """``h``, preferred actions and waits from the costs (a goal conjunct that needs
        longer than a deadline of the goal leaves counts as unreachable)."""
        base = 2 * self.n
        goal_left = min((left[q - base] for nodes in self.goal_nodes for q in nodes
                         if q - base in left), default=math.inf)
        h = 0.0
        unsat = 0
        needed = False
        waits: list[int] = []
        preferred: set[int] = set()
        seen: set[int] = set()
        running = set(active)
        holds: list[float] = []  # the motion goals' waits before their next control step

        def ready_process(i: int) -> bool:
            o = self.ops[i]
            return o.kind == "process" and o.index in running and acc[i] == 0.0

        def visit(node: int) -> None:
            if cost[node] == 0.0 or supp[node] < 0 or supp[node] in seen:
                return
            i = supp[node]
            seen.add(i)
            o = self.ops[i]
            way = steer.get(i, Steering())
            holds.append(way.hold)
            if o.kind == "action":
                late = [q for q in o.pre if cost[q] > 0.0]
                if not way.steps and all(q >= 2 * self.n and supp[q] >= 0 and
                                         ready_process(supp[q]) for q in late):
                    preferred.add(o.index)  # applicable, or its numbers are on their way
            preferred.update(a for a in way.actions if applicable(self.ct, a, facts, values))
            for q in o.pre:
                visit(q)

        for gi, g in enumerate(self.groups):
            if g.fn(facts, values):
                continue
            unsat += 1
            nodes = self.goal_nodes[gi]
            c = sum(cost[q] for q in nodes) if nodes else 1.0
            if any(need_t[q] > goal_left for q in nodes):
                c = math.inf
            toward = Steering()
            if self.goal_motion[gi] and c < math.inf:
                joint = self.second.joint(self.goal_motion[gi], nodes, facts, values, active,
                                          cost, left, toward)
                c = math.inf if joint is None or joint[1] > goal_left else c + joint[0]
                preferred.update(a for a in toward.actions if applicable(self.ct, a, facts, values))
                holds.append(toward.hold)
            h += self.config.unreachable_cost if c == math.inf else c
            late = [q for q in nodes if cost[q] > 0.0]
            if late and not toward.steps and all(supp[q] >= 0 and ready_process(supp[q])
                                                 for q in late):
                waits.append(gi)
            else:
                needed = True
            for q in nodes:
                visit(q)
        order = tuple(sorted(preferred))
        hold = min(holds, default=math.inf)
        return Evaluation(h, order, tuple(waits), needed, unsat,
                          hold if math.isfinite(hold) else 0.0)


def _partial(fn: PFn, values: Values, j: int) -> float:
    """``d fn / d v_j`` at ``values`` (central difference, step 1e-6 relative)."""
    x = values[j]
    h = 1e-6 * max(1.0, abs(x))
    up, down = list(values), list(values)
    up[j], down[j] = x + h, x - h
    return (fn(tuple(up)) - fn(tuple(down))) / (2.0 * h)


def _time_to(need: float, r: float, r2: float) -> float | None:
    """Time [s] to cover ``need`` at rate ``r`` changing at ``r2`` [1/s] (uniformly
    accelerated); None if the motion does not point that way (as far as the first and second
    orders tell). Decelerating motions that stop short are taken at their current rate (a
    relaxation stays optimistic)."""
    if need <= 0.0:
        return 0.0
    if r2 > 0.0:
        return (-r + math.sqrt(r * r + 2.0 * r2 * need)) / r2
    if r > 0.0:
        disc = r * r + 2.0 * r2 * need
        if r2 < 0.0 and disc >= 0.0:
            return (r - math.sqrt(disc)) / -r2
        return need / r
    return None


def _moved(eff: Effect) -> tuple[set[int], set[int]]:
    """Fluents an effect writes, and those it only increases or decreases."""
    moved: set[int] = set()
    other: set[int] = set()
    stack = [eff]
    while stack:
        e = stack.pop()
        for ne in e.numeric:
            moved.add(ne.fluent)
            if ne.op not in ("increase", "decrease"):
                other.add(ne.fluent)
        stack.extend(ce.effect for ce in e.conditional)
    return moved, moved - other


__all__ = ["NumericHeuristic"]
