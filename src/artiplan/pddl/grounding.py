"""Ground a domain and problem into the indexed :class:`~artiplan.pddl.task.Task`.

Steps, each cheap: check the problem against the domain; find the static predicates and
functions (never changed by any effect); instantiate every operator (static conjuncts checked as
parameters are bound); relaxed reachability prunes operators that can never apply; facts that can
never become true fold to ``FALSE``, facts true initially and never deleted to ``TRUE``; the
remaining facts are renumbered. ``GroundingStats.pruned`` counts the naive instances (every
parameter over every object of its type) that did not make it into the task.
"""

from __future__ import annotations

import time
from collections.abc import Callable

from artiplan.errors import InputError
from artiplan.pddl import syntax as s
from artiplan.pddl import task as t
from artiplan.pddl.checker import check_problem
from artiplan.pddl.durative import RUNNING, compile_durative
from artiplan.pddl.instantiate import GroundContext, expand, ground_condition, ground_num
from artiplan.pddl.operators import Instance, instantiate
from artiplan.pddl.reachability import reachable
from artiplan.pddl.renumber import (
    Renumbering,
    deleted_facts,
    fluents_in_condition,
    fluents_in_effect,
    fluents_in_num,
    fold_facts,
)
from artiplan.pddl.simplify import make_and
from artiplan.pddl.types import TypeHierarchy, objects_by_type
from artiplan.records import replace


def changed_symbols(domain: s.Domain) -> tuple[set[str], set[str]]:
    """Lower-case names of the predicates and functions some effect changes."""
    preds: set[str] = set()
    funcs: set[str] = set()

    def walk(e: s.EffectNode) -> None:
        if isinstance(e, s.AddEffect | s.DeleteEffect):
            preds.add(e.atom.predicate.lower())
        elif isinstance(e, s.NumericAssignment):
            funcs.add(e.target.name.lower())
        elif isinstance(e, s.EffectConjunction):
            for p in e.parts:
                walk(p)
        elif isinstance(e, s.ForallEffect | s.WhenEffect):
            walk(e.body if isinstance(e, s.ForallEffect) else e.effect)
        elif isinstance(e, s.Timed):
            walk(e.body)  # type: ignore[arg-type]

    for op in domain.operators:
        if op.effect is not None:
            walk(op.effect)
    return preds, funcs


def _context(domain: s.Domain, problem: s.Problem) -> tuple[GroundContext, dict[str, str]]:
    """The grounding context, and the display spelling of predicate and function names."""
    objects: dict[str, s.TypedName] = {}
    for o in (*domain.constants, *problem.objects):
        objects.setdefault(o.name.lower(), o)
    by_type = objects_by_type(TypeHierarchy.of(domain), tuple(objects.values()))
    changed_preds, changed_funcs = changed_symbols(domain)
    static_preds = frozenset(p.name.lower() for p in domain.predicates) - changed_preds
    static_funcs = frozenset(f.name.lower() for f in domain.functions) - changed_funcs
    static_facts = set()
    static_values: dict[tuple[str, ...], float] = {}
    for item in problem.init:
        if isinstance(item, s.AtomicFormula) and item.predicate.lower() in static_preds:
            static_facts.add((item.predicate.lower(), *(a.name.lower() for a in item.args)))
        elif isinstance(item, s.InitValue) and item.target.name.lower() in static_funcs:
            key = (item.target.name.lower(), *(a.name.lower() for a in item.target.args))
            static_values[key] = item.value
    ctx = GroundContext(
        objects_by_type=by_type,
        display={k: o.name for k, o in objects.items()},
        static_predicates=static_preds,
        static_facts=frozenset(static_facts),
        static_values=static_values,
        static_functions=static_funcs,
    )
    symbols = {p.name.lower(): p.name for p in domain.predicates}
    symbols.update({f.name.lower(): f.name for f in domain.functions})
    return ctx, symbols


def ground(domain: s.Domain, problem: s.Problem,
           check: Callable[[], None] | None = None) -> t.Task:
    """Ground ``problem`` of ``domain`` (both syntax trees) into an indexed task; ``check``
    is called before each operator schema (it may raise to stop, e.g. at a time limit)."""
    start = time.perf_counter()
    warnings = [*domain.warnings, *check_problem(domain, problem)]
    domain, durative = compile_durative(domain)
    ctx, symbols = _context(domain, problem)
    declared = {f.name.lower() for f in domain.functions}
    predicates = {p.name.lower() for p in domain.predicates}
    init_values: dict[int, float] = {}
    init_facts: set[int] = set()
    for item in problem.init:
        if isinstance(item, s.InitValue):
            key = (item.target.name.lower(), *(a.name.lower() for a in item.target.args))
            if key[0] in declared and key[0] not in ctx.static_functions:
                init_values[ctx.fluent(key)] = item.value
        elif item.predicate.lower() in predicates - ctx.static_predicates:  # undeclared: warned
            init_facts.add(ctx.fact((item.predicate.lower(),
                                     *(a.name.lower() for a in item.args))))
    instances: list[Instance] = []
    invariants: list[t.Condition] = []
    naive = 0
    for op in domain.operators:
        if check is not None:
            check()
        if op.kind == "constraint":  # an invariant for every binding, not an operator
            invariants += [t.TRUE if op.precondition is None else
                           ground_condition(ctx, op.precondition, b)
                           for b in expand(ctx, op.parameters, {})]
            continue
        found, count = instantiate(ctx, op)
        instances.extend(found)
        naive += count
    goal = t.TRUE if problem.goal is None else ground_condition(ctx, problem.goal, {})
    if durative:  # a plan ends with every durative action ended (as VAL requires)
        running = {n.lower() + RUNNING for n in durative}
        goal = make_and([goal, *(t.Not(t.Atom(i)) for key, i in ctx.fact_ids.items()
                                 if key[0] in running)])
    metric, metric_warning = _metric(ctx, problem.metric)
    warnings.extend(metric_warning)
    applicable, reached = reachable(instances, init_facts)
    kept = [inst for inst, ok in zip(instances, applicable, strict=True) if ok]
    task = _assemble(ctx, symbols, domain, problem, kept, init_facts, reached, init_values,
                     make_and(invariants), goal, metric, naive, warnings, start)
    return replace(task, durative=durative)


def _metric(ctx: GroundContext, spec: s.MetricSpec | None) -> tuple[t.Metric | None, list[str]]:
    if spec is None:
        return None, []
    if isinstance(spec.expr, s.Special) and spec.expr.name == "total-time":
        return t.Metric(spec.direction, None, uses_total_time=True), []
    try:
        return t.Metric(spec.direction, ground_num(ctx, spec.expr, {})), []
    except InputError:
        where = f"{spec.loc}: " if spec.loc is not None else ""
        return None, [f"{where}metric mixes total-time with other terms: not supported, ignored"]


Op = tuple[Instance, t.Condition, t.Effect]


def _fold(ctx: GroundContext, kept: list[Instance], init_facts: set[int], reached: set[int],
          goal: t.Condition) -> tuple[list[Op], t.Condition, Renumbering, list[int]]:
    """Fold constant facts and renumber the rest: operators still possible, goal, the facts'
    renumbering, kept old fact ids."""
    effects = [inst.effect.effect() for inst in kept]
    fact_map, kept_facts = fold_facts(len(ctx.fact_ids), init_facts, reached,
                                      deleted_facts(effects))
    by_facts = Renumbering(fact_map, None)
    ops: list[Op] = []
    for inst, eff in zip(kept, effects, strict=True):
        pre = by_facts.condition(inst.precondition)
        if pre != t.FALSE:
            ops.append((inst, pre, by_facts.effect(eff)))
    return ops, by_facts.condition(goal), by_facts, kept_facts


def _used_fluents(ops: list[Op], goal: t.Condition, metric: t.Metric | None,
                  init_values: dict[int, float]) -> list[int]:
    """Old ids of the fluents the task needs (initialised or read or changed), in order
    (``goal``: the goal and the invariants)."""
    used = set(init_values)
    used.update(fluents_in_condition(goal))
    if metric is not None and metric.expr is not None:
        used.update(fluents_in_num(metric.expr))
    for inst, pre, eff in ops:
        used.update(fluents_in_condition(pre))
        used.update(fluents_in_effect(eff))
        for c in inst.effect.continuous:
            used.add(c.fluent)
            used.update(fluents_in_num(c.rate))
    return sorted(used)


def _operators(
    ctx: GroundContext, ops: list[Op], by_fluents: Renumbering
) -> tuple[list[t.GroundAction], list[t.GroundAction], list[t.GroundProcess]]:
    actions: list[t.GroundAction] = []
    events: list[t.GroundAction] = []
    processes: list[t.GroundProcess] = []
    for inst, pre, eff in ops:
        args = tuple(ctx.display.get(a, a) for a in inst.args)
        if by_fluents.fluents is not None:
            pre, eff = by_fluents.condition(pre), by_fluents.effect(eff)
        if inst.op.kind == "process":
            processes.append(t.GroundProcess(inst.op.name, args, pre,
                                             by_fluents.continuous(inst.effect.continuous), eff))
        elif inst.op.kind == "event":
            events.append(t.GroundAction(inst.op.name, args, pre, eff, "event"))
        else:
            actions.append(t.GroundAction(inst.op.name, args, pre, eff))
    return actions, events, processes


def _assemble(
    ctx: GroundContext, symbols: dict[str, str], domain: s.Domain, problem: s.Problem,
    kept: list[Instance], init_facts: set[int], reached: set[int],
    init_values: dict[int, float], invariant: t.Condition, goal: t.Condition,
    metric: t.Metric | None, naive: int, warnings: list[str], start: float,
) -> t.Task:
    ops, goal, by_facts, kept_facts = _fold(ctx, kept, init_facts, reached, goal)
    fact_map = by_facts.facts
    invariant = by_facts.condition(invariant)
    old_fluents = _used_fluents(ops, t.And((goal, invariant)), metric, init_values)
    by_fluents = Renumbering(
        {i: t.Atom(i) for i in range(len(kept_facts))},
        None if len(old_fluents) == len(ctx.fluent_ids)
        else {old: new for new, old in enumerate(old_fluents)},
    )
    actions, events, processes = _operators(ctx, ops, by_fluents)
    fact_keys, fluent_keys = list(ctx.fact_ids), list(ctx.fluent_ids)
    facts = tuple(_name(ctx, symbols, fact_keys[old]) for old in kept_facts)
    fluents = tuple(_name(ctx, symbols, fluent_keys[old]) for old in old_fluents)
    if metric is not None and metric.expr is not None:
        metric = t.Metric(metric.direction, by_fluents.num(metric.expr), metric.uses_total_time)
    stats = t.GroundingStats(
        facts=len(facts), fluents=len(fluents), actions=len(actions), events=len(events),
        processes=len(processes), pruned=naive - len(ops), seconds=time.perf_counter() - start,
    )
    return t.Task(
        domain_name=domain.name,
        problem_name=problem.name,
        facts=facts,
        fluents=fluents,
        init_facts=frozenset(m.fact for f in init_facts if isinstance(m := fact_map[f], t.Atom)),
        init_values=tuple(init_values.get(old) for old in old_fluents),
        goal=by_fluents.condition(goal),
        invariants=_parts(by_fluents.condition(invariant)),
        actions=tuple(actions),
        events=tuple(events),
        processes=tuple(processes),
        metric=metric,
        stats=stats,
        warnings=tuple(warnings),
    )


def _parts(c: t.Condition) -> tuple[t.Condition, ...]:
    """A conjunction's parts (none for ``TRUE``)."""
    if c == t.TRUE:
        return ()
    return c.parts if isinstance(c, t.And) else (c,)


def _name(ctx: GroundContext, symbols: dict[str, str], key: tuple[str, ...]) -> str:
    return "(" + " ".join((symbols.get(key[0], key[0]),
                           *(ctx.display.get(a, a) for a in key[1:]))) + ")"
