"""Renumber facts and fluents of ground operators after pruning, folding the facts that turned
out constant (never reachable: ``FALSE``; true initially and never deleted: ``TRUE``)."""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from artiplan.pddl import task as t
from artiplan.pddl.simplify import make_and, make_not, make_or
from artiplan.records import dataclass


@dataclass(frozen=True)
class Renumbering:
    """Old fact id -> its condition in the new numbering; old fluent id -> new id."""

    facts: dict[int, t.Condition]
    fluents: dict[int, int] | None  # None: fluents keep their numbers

    def condition(self, c: t.Condition) -> t.Condition:
        """``c`` renumbered and simplified."""
        if isinstance(c, t.Atom):
            return self.facts[c.fact]
        if isinstance(c, t.And):
            return make_and(self.condition(p) for p in c.parts)
        if isinstance(c, t.Or):
            return make_or(self.condition(p) for p in c.parts)
        if isinstance(c, t.Not):
            return make_not(self.condition(c.operand))
        if isinstance(c, t.Comparison):
            return t.Comparison(c.op, self.num(c.left), self.num(c.right))
        return c

    def num(self, e: t.NumExpr) -> t.NumExpr:
        """``e`` with fluents renumbered."""
        if self.fluents is None or isinstance(e, t.Const):
            return e
        if isinstance(e, t.FluentRef):
            return t.FluentRef(self.fluents[e.index])
        if isinstance(e, t.BinOp):
            return t.BinOp(e.op, self.num(e.left), self.num(e.right))
        if isinstance(e, t.Neg):
            return t.Neg(self.num(e.operand))
        return e

    def effect(self, e: t.Effect) -> t.Effect:
        """``e`` renumbered; parts on folded facts dropped, ``TRUE`` conditions inlined."""
        add = [m.fact for f in e.add if isinstance(m := self.facts[f], t.Atom)]
        delete = [m.fact for f in e.delete if isinstance(m := self.facts[f], t.Atom)]
        numeric = list(e.numeric) if self.fluents is None else [
            t.NumericEffect(n.op, self.fluents[n.fluent], self.num(n.expr)) for n in e.numeric]
        conditional: list[t.ConditionalEffect] = []
        for ce in e.conditional:
            cond = self.condition(ce.condition)
            inner = self.effect(ce.effect)
            if cond == t.FALSE or inner == t.EMPTY_EFFECT:
                continue
            if cond == t.TRUE:
                add += inner.add
                delete += inner.delete
                numeric += inner.numeric
                conditional += inner.conditional
            else:
                conditional.append(t.ConditionalEffect(cond, inner))
        return t.Effect(tuple(add), tuple(delete), tuple(numeric), tuple(conditional))

    def continuous(self, effects: Iterable[t.ContinuousEffect]) -> tuple[t.ContinuousEffect, ...]:
        """Continuous effects with fluents renumbered."""
        if self.fluents is None:
            return tuple(effects)
        return tuple(t.ContinuousEffect(self.fluents[c.fluent], self.num(c.rate))
                     for c in effects)


def fold_facts(n_facts: int, init: set[int], reached: set[int], deleted: set[int]
               ) -> tuple[dict[int, t.Condition], list[int]]:
    """Old fact id -> folded condition or new ``Atom``; and the kept old ids in new order."""
    mapping: dict[int, t.Condition] = {}
    kept: list[int] = []
    for old in range(n_facts):
        if old not in reached:
            mapping[old] = t.FALSE
        elif old in init and old not in deleted:
            mapping[old] = t.TRUE
        else:
            mapping[old] = t.Atom(len(kept))
            kept.append(old)
    return mapping, kept


def deleted_facts(effects: Iterable[t.Effect]) -> set[int]:
    """Every fact some effect (or conditional part) deletes."""
    out: set[int] = set()
    for e in effects:
        out.update(e.delete)
        out |= deleted_facts(ce.effect for ce in e.conditional)
    return out


def fluents_in_num(e: t.NumExpr) -> Iterator[int]:
    """Fluent ids read by ``e``."""
    if isinstance(e, t.FluentRef):
        yield e.index
    elif isinstance(e, t.BinOp):
        yield from fluents_in_num(e.left)
        yield from fluents_in_num(e.right)
    elif isinstance(e, t.Neg):
        yield from fluents_in_num(e.operand)


def fluents_in_condition(c: t.Condition) -> Iterator[int]:
    """Fluent ids read by ``c``."""
    if isinstance(c, t.Comparison):
        yield from fluents_in_num(c.left)
        yield from fluents_in_num(c.right)
    elif isinstance(c, t.And | t.Or):
        for p in c.parts:
            yield from fluents_in_condition(p)
    elif isinstance(c, t.Not):
        yield from fluents_in_condition(c.operand)


def fluents_in_effect(e: t.Effect) -> Iterator[int]:
    """Fluent ids read or changed by ``e``."""
    for n in e.numeric:
        yield n.fluent
        yield from fluents_in_num(n.expr)
    for ce in e.conditional:
        yield from fluents_in_condition(ce.condition)
        yield from fluents_in_effect(ce.effect)
