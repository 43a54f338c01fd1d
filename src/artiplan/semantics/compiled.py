"""The kernel's view of a grounded task: conditions and effects as generated Python functions.

Facts are a bit mask (an ``int``), values a tuple of floats. Every distinct comparison of the
task is numbered once (:class:`Comparison`: ``p op 0`` with ``p = left - right``, its linear form
when it has one); conditions become ``lambda F, V: ...`` read with the task's
:class:`~artiplan.tolerances.Tolerances`; effects become functions of the state *before* the
happening (PDDL 2.1: deletes before adds, every right-hand side from the pre-state). Process
preconditions are read *snapped* (a difference within ``tol.zero`` counts as exactly 0): which
processes run just after a time point is then decided on the flow (``kernel``).

Compiling costs a few milliseconds per hundred operators and happens once per task.
"""

from __future__ import annotations

import operator
from collections.abc import Callable

from artiplan.pddl.task import (
    And,
    BinOp,
    Condition,
    Effect,
    GroundAction,
    Not,
    NumExpr,
    Task,
    Truth,
)
from artiplan.pddl.task import Atom as _Atom
from artiplan.pddl.task import Comparison as _Comparison
from artiplan.records import dataclass, field, replace
from artiplan.semantics.cache import cached, per_task
from artiplan.semantics.walks import (
    Linear,
    comparison_source,
    condition_parts,
    condition_source,
    expr_source,
    fluents_of,
    linear,
    source_definitions,
    source_function,
)
from artiplan.tolerances import VAL, Tolerances
from artiplan.typenames import Any

CondFn = Callable[[int, tuple[float, ...]], bool]
EffectFn = Callable[[int, tuple[float, ...]], tuple[int, tuple[float, ...]]]
#: ``(F, V) -> (add mask, delete mask, [(fluent, op, right-hand side)])``: an effect's parts,
#: to apply several actions in parallel.
PartsFn = Callable[[int, tuple[float, ...]], tuple[int, int, list[tuple[int, str, float]]]]


@dataclass(frozen=True)
class Comparison:
    """``p op 0`` with ``p = left - right``.

    ``single``: ``(fluent, a, b)`` when ``p = a * v[fluent] + b`` (most comparisons: their roots
    are found for many at once, vectorised).
    """

    op: str
    expr: NumExpr
    linear: Linear | None
    fluents: frozenset[int]
    single: tuple[int, float, float] | None


@dataclass
class ComparisonTable:
    """The task's distinct comparisons, numbered."""

    items: list[Comparison] = field(default_factory=list)
    index: dict[tuple[str, NumExpr], int] = field(default_factory=dict)

    def add(self, comp: _Comparison) -> int:
        p: NumExpr = BinOp("-", comp.left, comp.right)
        key = (comp.op, p)  # structural: hashing the frozen tree is cheaper than its repr
        found = self.index.get(key)
        if found is None:
            lin = linear(p)
            single = None
            if lin is not None and len(lin[0]) == 1:
                (f, a), = lin[0].items()
                single = (f, a, lin[1])
            found = self.index[key] = len(self.items)
            self.items.append(Comparison(comp.op, p, lin, fluents_of(p), single))
        return found


def _snapped(op: str, diff: str, zero: float) -> str:
    """Source of :meth:`Tolerances.snapped` for ``diff op 0``."""
    return {">": f"({diff} > {zero!r})", ">=": f"({diff} >= {-zero!r})",
            "<": f"({diff} < {-zero!r})", "<=": f"({diff} <= {zero!r})"}.get(
        op, f"(abs({diff}) <= {zero!r})")


def compile_condition(
    cond: Condition, comps: ComparisonTable, tol: Tolerances, snap: bool = False
) -> tuple[CondFn, frozenset[int]]:
    """``cond`` as ``(F, V) -> bool`` (point truth with ``tol``, or snapped), and the ids of
    the comparisons it reads."""
    used: set[int] = set()

    def comparison(c: _Comparison) -> str:
        used.add(comps.add(c))
        if snap:
            return _snapped(c.op, f"({expr_source(c.left)} - {expr_source(c.right)})", tol.zero)
        return comparison_source(c, tol)

    src = condition_source(cond, comparison)
    fn: CondFn = source_function(f"lambda F, V: {src}")
    return fn, frozenset(used)


def fact_literals(cond: Condition) -> tuple[int, int] | None:
    """(required mask, forbidden mask) of the fact literals at the top level of ``cond``;
    None if it can never hold. The rest of the condition is its function's business."""
    req = forb = 0
    for part in cond.parts if isinstance(cond, And) else (cond,):
        if isinstance(part, Truth) and not part.value:
            return None
        if isinstance(part, _Atom):
            req |= 1 << part.fact
        elif isinstance(part, Not) and isinstance(part.operand, _Atom):
            forb |= 1 << part.operand.fact
    return req, forb


_RHS = {"assign": "{e}", "increase": "W[{i}] + {e}", "decrease": "W[{i}] - {e}",
        "scale-up": "W[{i}] * {e}", "scale-down": "W[{i}] / {e}"}
#: The same updates as functions ``(old value, right-hand side) -> new value``.
UPDATE: dict[str, Callable[[float, float], float]] = {
    "assign": lambda _old, rhs: rhs, "increase": operator.add, "decrease": operator.sub,
    "scale-up": operator.mul, "scale-down": operator.truediv}


def _effect_lines(eff: Effect, indent: str, cond_src: Callable[[Condition], str],
                  lines: list[str], parts: bool) -> None:
    add, dele = sum(1 << f for f in eff.add), sum(1 << f for f in eff.delete)
    if add:
        lines.append(f"{indent}add |= {add}")
    if dele:
        lines.append(f"{indent}dele |= {dele}")
    for ne in eff.numeric:
        e = expr_source(ne.expr)
        if parts:
            lines.append(f"{indent}U.append(({ne.fluent}, {ne.op!r}, {e}))")
        else:
            lines.append(f"{indent}W[{ne.fluent}] = {_RHS[ne.op].format(i=ne.fluent, e=e)}")
    for ce in eff.conditional:
        lines.append(f"{indent}if {cond_src(ce.condition)}:")
        lines.append(f"{indent}    pass")
        _effect_lines(ce.effect, indent + "    ", cond_src, lines, parts)


def effect_sources(eff: Effect, comps: ComparisonTable, tol: Tolerances) -> tuple[str, str]:
    """Sources of ``eff`` as ``_eff(F, V) -> (F2, V2)`` and as its parts ``_parts`` (see
    :data:`PartsFn`); conditions of conditional effects read with ``tol`` in the state
    before the happening (their comparisons are entered in ``comps`` now)."""
    def cond_src(c: Condition) -> str:
        return condition_source(c, lambda comp: (comps.add(comp), comparison_source(comp, tol))[1])

    apply = ["def _eff(F, V):", "    add = 0", "    dele = 0", "    W = list(V)"]
    _effect_lines(eff, "    ", cond_src, apply, parts=False)
    apply.append("    return (F & ~dele) | add, tuple(W)")
    split = ["def _parts(F, V):", "    add = 0", "    dele = 0", "    U = []"]
    _effect_lines(eff, "    ", cond_src, split, parts=True)
    split.append("    return add, dele, U")
    return "\n".join(apply), "\n".join(split)


def _compile_on_first_call(op: Operator, field_name: str, source: str, name: str) -> None:
    """Set ``op.<field_name>`` to a stub that compiles the function ``name`` of ``source``
    when first called and puts it in its place: a search applies about half of a task's
    operators, and parallel effects (``parts``) rarely, so most effects are never compiled."""
    done: list[Callable[..., Any]] = []

    def first(*args: Any) -> Any:
        if not done:
            done.append(source_definitions(source)[name])
            object.__setattr__(op, field_name, done[0])
        return done[0](*args)

    object.__setattr__(op, field_name, first)


def is_noop(action: GroundAction) -> bool:
    """True for an action with no effect at all (the domains' ``observe``)."""
    eff = action.effect
    return not (eff.add or eff.delete or eff.numeric or eff.conditional)


def constant_assigns(eff: Effect) -> set[int]:
    """Fluents ``eff`` only assigns constants to (unconditionally; no other change)."""
    const = {ne.fluent for ne in eff.numeric if ne.op == "assign" and not fluents_of(ne.expr)}
    other = written_fluents(eff) - const
    for ce in eff.conditional:
        other |= written_fluents(ce.effect)
    return const - other


def written_fluents(eff: Effect) -> set[int]:
    """Fluents an instantaneous effect may change."""
    out = {ne.fluent for ne in eff.numeric}
    for ce in eff.conditional:
        out |= written_fluents(ce.effect)
    return out


@dataclass(frozen=True)
class Operator:
    """An action or an event: precondition and effect compiled, with a cheap fact filter."""

    index: int
    signature: str
    name: str
    args: tuple[str, ...]
    pre: CondFn
    pre_comps: frozenset[int]
    req: int
    forb: int
    effect: EffectFn
    parts: PartsFn
    noop: bool
    source: GroundAction
    #: The fluents the effect may change (conditionally or not)
    writes: frozenset[int] = frozenset()
    #: The fluents it only ever sets to a constant (e.g. ``(assign (held-index) 1)``)
    resets: frozenset[int] = frozenset()


@dataclass(frozen=True)
class Process:
    """A process: its (snapped) precondition and its rates, per fluent (expression, linear
    form or None). ``pre_class``: processes with equal preconditions share one; ``adds`` and
    ``deletes``: facts a process sets while active (the paper's quirk)."""

    index: int
    signature: str
    pre: CondFn
    pre_comps: frozenset[int]
    req: int
    forb: int
    rates: tuple[tuple[int, NumExpr, Linear | None], ...]
    pre_class: int
    reads: frozenset[int]
    adds: int = 0
    deletes: int = 0


@dataclass
class CompiledTask:
    """Everything the kernel evaluates, compiled once per task (and ``tol``)."""

    task: Task
    tol: Tolerances
    comps: ComparisonTable
    actions: list[Operator]
    events: list[Operator]
    processes: list[Process]
    goal: CondFn
    goal_comps: frozenset[int]
    init_facts: int
    init_values: tuple[float, ...]
    #: comparisons that can change the dynamics (event and process preconditions)
    dynamic: frozenset[int]
    #: comparisons watched while waiting: the dynamic ones (not those only re-arms read), the
    #: goal's, action preconditions'
    watched: frozenset[int]
    #: per fluent, the watched and dynamic comparisons that read it
    fluent_comps: dict[int, tuple[int, ...]]
    #: the goal and action preconditions are read snapped, without the slack (the planner's)
    strict: bool = False
    #: invariants (read with ``tol`` at a point), with the comparisons each reads
    invariants: tuple[tuple[CondFn, frozenset[int]], ...] = ()
    #: guard facts (mask): read only by events, as "fired once until re-armed" (see
    #: :func:`guard_facts`); the planner leaves them out of its duplicate key
    guards: int = 0
    #: events that only re-arm guards: nothing else reads what they change
    rearms: frozenset[int] = frozenset()
    #: dynamic comparisons read by events other than re-arms (the ones actions keep clear of)
    spaced: frozenset[int] = frozenset()


def _operator(i: int, op: GroundAction, comps: ComparisonTable, tol: Tolerances,
              strict: bool = False) -> Operator:
    pre, used = compile_condition(op.precondition, comps, tol, snap=strict)
    req, forb = fact_literals(op.precondition) or (0, 0)
    apply, split = effect_sources(op.effect, comps, tol)
    out = Operator(i, op.signature, op.name, op.args, pre, used, req, forb, _unset, _unset,
                   is_noop(op), op, frozenset(written_fluents(op.effect)),
                   frozenset(constant_assigns(op.effect)))
    _compile_on_first_call(out, "effect", apply, "_eff")
    _compile_on_first_call(out, "parts", split, "_parts")
    return out


def guard_facts(task: Task) -> tuple[int, frozenset[int]]:
    """Guard facts (mask) and the events that only re-arm them (cached per task).

    A guard ``g`` is read by no action, process, invariant or goal, and every event that reads
    it either requires ``not g`` at the top level and adds ``g`` (it fires once until
    re-armed) or only deletes guards (a re-arm, which may read them anywhere). The wrap flags
    of artiplan's encodings are guards: under exact semantics they never change what happens,
    they make VAL see a wrap falsify its precondition (docs/encodings.md, "Wrap-around").
    """
    return per_task(task, "guards", lambda: _guard_facts(task))


def _guard_facts(task: Task) -> tuple[int, frozenset[int]]:
    read = [task.goal, *task.invariants, *(o.precondition for o in task.actions),
            *(p.precondition for p in task.processes)]
    others: set[int] = set().union(*(condition_parts(c)[0] for c in read))
    candidates: set[int] = set()
    for e in task.events:
        forb = (fact_literals(e.precondition) or (0, 0))[1]
        candidates |= {f for f in e.effect.add if forb >> f & 1}
    candidates -= others
    changed = True
    while changed:  # dropping a candidate can disqualify a re-arm that deletes it
        changed, rearms = False, set()
        for i, e in enumerate(task.events):
            eff = e.effect
            if eff.delete and not (eff.add or eff.numeric or eff.conditional) \
                    and set(eff.delete) <= candidates:
                rearms.add(i)  # a re-arm: it may read guards anywhere in its precondition
                continue
            forb = (fact_literals(e.precondition) or (0, 0))[1]
            bad = {f for f in condition_parts(e.precondition)[0] & candidates
                   if not (forb >> f & 1 and f in eff.add)}
            if bad:
                candidates -= bad
                changed = True
    return sum(1 << f for f in candidates), frozenset(rearms)


def _unset(facts: int, values: tuple[float, ...]) -> Any:
    raise AssertionError("replaced by _compile_on_first_call")


def compile_task(task: Task, tol: Tolerances = VAL, strict: bool = False) -> CompiledTask:
    """The compiled task (cached per task, tolerances and ``strict``).

    ``strict`` (the planner's view): the goal and the action preconditions are read snapped
    (exactly, up to ``tol.zero`` of rounding; a strict comparison must hold by more), so a
    plan never leans on the slack; events and the conditions of conditional effects are still
    read with ``tol``, as a validator reads them.
    """
    def build() -> CompiledTask:
        # the planner's and the validator's views of one task differ only in how the goal and
        # the action preconditions read comparisons: the second view is the first one re-read
        other = cached(task, ("compiled", tol, not strict))
        return _compile(task, tol, strict) if other is None else _reread(other, strict)

    return per_task(task, ("compiled", tol, strict), build)


def _reread(other: CompiledTask, strict: bool) -> CompiledTask:
    """``other`` (the same task and tolerances) with its goal and action preconditions read
    ``strict`` or not. Everything else (comparison table, events, processes, invariants,
    effects) is the same in both views and shared."""
    comps, tol = other.comps, other.tol
    actions = []
    for op in other.actions:
        pre, used = compile_condition(op.source.precondition, comps, tol, snap=strict)
        copy = replace(op, pre=pre, pre_comps=used)
        _follow(op, copy, "effect")
        _follow(op, copy, "parts")
        actions.append(copy)
    goal, goal_comps = compile_condition(other.task.goal, comps, tol, snap=strict)
    return replace(other, actions=actions, goal=goal, goal_comps=goal_comps, strict=strict)


def _follow(src: Operator, dst: Operator, field_name: str) -> None:
    """``dst.<field_name>`` calls ``src``'s (compiling it on the first call of either) and
    then takes its place."""
    def first(*args: Any) -> Any:
        out = getattr(src, field_name)(*args)
        object.__setattr__(dst, field_name, getattr(src, field_name))
        return out

    object.__setattr__(dst, field_name, first)


def _compile(task: Task, tol: Tolerances, strict: bool) -> CompiledTask:
    comps = ComparisonTable()
    actions = [_operator(i, a, comps, tol, strict) for i, a in enumerate(task.actions)]
    events = [_operator(i, e, comps, tol) for i, e in enumerate(task.events)]
    processes = []
    classes: dict[Condition, int] = {}
    shared: dict[int, tuple[CondFn, frozenset[int]]] = {}
    for i, p in enumerate(task.processes):
        # equal preconditions (a link's gravity carried to each tip-ward link) share one
        # compiled condition and one class: its truth is computed once per state
        cls = classes.setdefault(p.precondition, len(classes))
        if cls not in shared:
            shared[cls] = compile_condition(p.precondition, comps, tol, snap=True)
        pre, used = shared[cls]
        req, forb = fact_literals(p.precondition) or (0, 0)
        rates = tuple((ce.fluent, ce.rate, linear(ce.rate)) for ce in p.continuous)
        reads = frozenset(condition_parts(p.precondition)[1])
        processes.append(Process(i, p.signature, pre, used, req, forb, rates, cls, reads,
                                 sum(1 << f for f in p.discrete.add),
                                 sum(1 << f for f in p.discrete.delete)))
    goal, goal_comps = compile_condition(task.goal, comps, tol, snap=strict)
    invariants = tuple(compile_condition(c, comps, tol) for c in task.invariants)
    guards, rearms = guard_facts(task)
    spaced = frozenset().union(*(e.pre_comps for i, e in enumerate(events) if i not in rearms),
                               *(p.pre_comps for p in processes),
                               *(used for _, used in invariants))
    dynamic = spaced.union(*(events[i].pre_comps for i in rearms))
    # a re-arm changes nothing a wait could be for: its comparisons are not watched
    watched = spaced | goal_comps | frozenset().union(*(a.pre_comps for a in actions))
    fluent_comps: dict[int, list[int]] = {}
    for cid in sorted(watched | dynamic):
        for f in comps.items[cid].fluents:
            fluent_comps.setdefault(f, []).append(cid)
    init_values = tuple(float("nan") if v is None else float(v) for v in task.init_values)
    return CompiledTask(
        task=task, tol=tol, comps=comps, actions=actions, events=events, processes=processes,
        goal=goal, goal_comps=goal_comps, init_facts=sum(1 << f for f in task.init_facts),
        init_values=init_values, dynamic=dynamic, watched=watched,
        fluent_comps={f: tuple(c) for f, c in fluent_comps.items()}, strict=strict,
        invariants=invariants, guards=guards, rearms=rearms, spaced=spaced,
    )
