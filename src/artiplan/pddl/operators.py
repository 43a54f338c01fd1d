"""Instantiate operator schemas, binding parameters one at a time.

The static atoms, negated static atoms and (in)equalities of a precondition's top-level
conjunction are checked as soon as their arguments are bound, so an operator like
``start-increase(?l1 ?l2 - link ?x - plane)`` with ``(connected ?l1 ?l2)`` is never built for
the n*n pairs of links that are not neighbours.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator

from artiplan.pddl import syntax as s
from artiplan.pddl import task as t
from artiplan.pddl.instantiate import (
    Binding,
    EffectParts,
    GroundContext,
    ground_condition,
    ground_effect,
)
from artiplan.records import dataclass

Check = Callable[[Binding], bool]


@dataclass(frozen=True)
class Instance:
    """One ground operator before reachability: its binding and parts."""

    op: s.Operator
    args: tuple[str, ...]
    precondition: t.Condition
    effect: EffectParts


def conjuncts(f: s.Formula | None) -> list[s.Formula]:
    """The top-level conjuncts of ``f`` (nested ``and`` flattened)."""
    if f is None:
        return []
    if isinstance(f, s.Conjunction):
        return [c for p in f.parts for c in conjuncts(p)]
    return [f]


def _static_check(ctx: GroundContext, f: s.Formula) -> tuple[set[str], Check] | None:
    """A fast test for a static conjunct, with the variables it needs; None if not static."""
    positive = True
    if isinstance(f, s.Negation):
        positive, f = False, f.operand
    if isinstance(f, s.AtomicFormula) and f.predicate.lower() in ctx.static_predicates:
        pred = f.predicate.lower()
        terms = [(isinstance(a, s.Variable), a.name.lower()) for a in f.args]
        facts = ctx.static_facts

        def check_atom(b: Binding) -> bool:
            key = (pred, *(b[n] if var else n for var, n in terms))
            return (key in facts) == positive

        return {n for var, n in terms if var}, check_atom
    if isinstance(f, s.Equals):
        left = (isinstance(f.left, s.Variable), f.left.name.lower())
        right = (isinstance(f.right, s.Variable), f.right.name.lower())

        def check_eq(b: Binding) -> bool:
            lv = b[left[1]] if left[0] else left[1]
            rv = b[right[1]] if right[0] else right[1]
            return (lv == rv) == positive

        return {n for var, n in (left, right) if var}, check_eq
    return None


def bindings(ctx: GroundContext, op: s.Operator) -> Iterator[Binding]:
    """Parameter bindings of ``op`` that pass its static top-level conjuncts."""
    names = [p.name.lower() for p in op.parameters]
    domains = [ctx.objects_of(p.types) for p in op.parameters]
    checks_at: list[list[Check]] = [[] for _ in names]
    always: list[Check] = []
    for c in conjuncts(op.precondition):
        found = _static_check(ctx, c)
        if found is None:
            continue
        needed, check = found
        if not needed:
            always.append(check)
            continue
        depth = max(names.index(v) for v in needed if v in names)
        checks_at[depth].append(check)
    if not all(c({}) for c in always):
        return
    binding: Binding = {}

    def extend(i: int) -> Iterator[Binding]:
        if i == len(names):
            yield dict(binding)
            return
        for obj in domains[i]:
            binding[names[i]] = obj
            if all(c(binding) for c in checks_at[i]):
                yield from extend(i + 1)
        binding.pop(names[i], None)

    yield from extend(0)


def instantiate(ctx: GroundContext, op: s.Operator) -> tuple[list[Instance], int]:
    """The ground instances of ``op`` whose precondition is not statically false, and the
    number of naive instances (every parameter over every object of its type)."""
    out: list[Instance] = []
    for b in bindings(ctx, op):
        pre = t.TRUE if op.precondition is None else ground_condition(ctx, op.precondition, b)
        if pre == t.FALSE:
            continue
        parts = EffectParts()
        if op.effect is not None:
            ground_effect(ctx, op.effect, b, parts)
        args = tuple(b[p.name.lower()] for p in op.parameters)
        out.append(Instance(op, args, pre, parts))
    return out, math.prod(len(ctx.objects_of(p.types)) for p in op.parameters)
