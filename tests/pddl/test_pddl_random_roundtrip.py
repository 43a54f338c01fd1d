"""Random (seeded) domains through the writer and back: every construct, nested at random."""

from __future__ import annotations

import random

import pytest

from artiplan.pddl import ground, parse_domain, parse_problem, write_domain
from artiplan.pddl import syntax as s
from artiplan.pddl import task as tk

PREDICATES = {"p": 0, "q": 1, "r": 2}
FUNCTIONS = {"f": 0, "g": 1}
TYPES = (s.TypedName("a", ("t",)), s.TypedName("b", ("t",)), s.TypedName("t"))


class Gen:
    """Random well-formed trees over the declarations above (type ``t`` everywhere)."""

    def __init__(self, seed: int) -> None:
        self.rng = random.Random(seed)
        self.n = 0

    def fresh(self) -> str:
        self.n += 1
        return f"?v{self.n}"

    def term(self, scope: list[str]) -> s.Term:
        if scope and self.rng.random() < 0.8:
            return s.Variable(self.rng.choice(scope))
        return s.Name("C")

    def atom(self, scope: list[str]) -> s.AtomicFormula:
        name = self.rng.choice(sorted(PREDICATES))
        return s.AtomicFormula(name, tuple(self.term(scope) for _ in range(PREDICATES[name])))

    def num(self, scope: list[str], depth: int, time: bool = False) -> s.NumExpr:
        roll = self.rng.random()
        if depth <= 0 or roll < 0.3:
            if self.rng.random() < 0.5:
                return s.Number(self.rng.choice([0.0, 1.0, -3.0, 0.5, 1e-3, 123.25]))
            name = self.rng.choice(sorted(FUNCTIONS))
            return s.FunctionTerm(name, tuple(self.term(scope) for _ in range(FUNCTIONS[name])))
        if roll < 0.4:
            return s.Minus(self.num(scope, depth - 1))
        op = self.rng.choice(["+", "-", "*", "/"])
        k = self.rng.choice([2, 3]) if op in "+*" else 2
        return s.Arithmetic(op, tuple(self.num(scope, depth - 1) for _ in range(k)))

    def formula(self, scope: list[str], depth: int) -> s.Formula:
        roll = self.rng.random()
        if depth <= 0 or roll < 0.25:
            return self.atom(scope)
        if roll < 0.35:
            return s.Compare(self.rng.choice(["<", "<=", ">", ">=", "="]),
                             self.num(scope, 2), self.num(scope, 2))
        if roll < 0.42 and scope:
            return s.Equals(self.term(scope), self.term(scope))
        if roll < 0.5:
            return s.Negation(self.formula(scope, depth - 1))
        if roll < 0.65:
            parts = tuple(self.formula(scope, depth - 1) for _ in range(self.rng.randint(0, 3)))
            return (s.Conjunction if self.rng.random() < 0.5 else s.Disjunction)(parts)
        if roll < 0.75:
            return s.Implication(self.formula(scope, depth - 1), self.formula(scope, depth - 1))
        v = self.fresh()
        body = self.formula([*scope, v], depth - 1)
        return s.Quantified(self.rng.choice(["exists", "forall"]), (s.TypedName(v, ("t",)),),
                            body)

    def effect(self, scope: list[str], depth: int) -> s.EffectNode:
        roll = self.rng.random()
        if depth <= 0 or roll < 0.3:
            return (s.AddEffect if self.rng.random() < 0.5 else s.DeleteEffect)(self.atom(scope))
        if roll < 0.5:
            target = self.num(scope, 0)
            while not isinstance(target, s.FunctionTerm):
                target = self.num(scope, 0)
            op = self.rng.choice(["assign", "increase", "decrease", "scale-up", "scale-down"])
            return s.NumericAssignment(op, target, self.num(scope, 2))
        if roll < 0.7:
            return s.EffectConjunction(tuple(self.effect(scope, depth - 1)
                                             for _ in range(self.rng.randint(0, 3))))
        if roll < 0.85:
            return s.WhenEffect(self.formula(scope, 2), self.effect(scope, depth - 1))
        v = self.fresh()
        return s.ForallEffect((s.TypedName(v, ("t",)),), self.effect([*scope, v], depth - 1))

    def domain(self) -> s.Domain:
        ops = []
        for i in range(4):
            params = [self.fresh() for _ in range(self.rng.randint(0, 2))]
            kind = self.rng.choice(["action", "event"])
            ops.append(s.Operator(kind, f"op{i}", tuple(s.TypedName(v, ("t",)) for v in params),
                                  self.formula(params, 3), self.effect(params, 3)))
        rate = s.Arithmetic("*", (s.Special("#t"), self.num(["?x"], 2)))
        ops.append(s.Operator("process", "flow", (s.TypedName("?x", ("t",)),),
                              self.formula(["?x"], 2),
                              s.NumericAssignment("increase", s.FunctionTerm("f"), rate)))
        return s.Domain(
            "random", (":adl", ":numeric-fluents", ":time"), TYPES[2:],
            (s.TypedName("C", ("t",)),),
            tuple(s.PredicateDecl(p, tuple(s.TypedName(f"?x{j}", ("t",)) for j in range(n)))
                  for p, n in sorted(PREDICATES.items())),
            tuple(s.FunctionDecl(f, tuple(s.TypedName(f"?x{j}", ("t",)) for j in range(n)))
                  for f, n in sorted(FUNCTIONS.items())),
            tuple(ops),
        )


@pytest.mark.parametrize("seed", range(40))
def test_random_domain_round_trip_and_grounds(seed: int) -> None:
    tree = Gen(seed).domain()
    text = write_domain(tree)
    parsed = parse_domain(text, f"random{seed}.pddl")
    assert parsed == tree
    assert write_domain(parsed) == text
    problem = parse_problem("(define (problem r) (:domain random) (:objects o1 o2 - t)"
                            "(:init (q o1) (r o1 C) (= (f) 1) (= (g o1) 2) (= (g o2) 0.5)"
                            " (= (g C) 3)) (:goal (p)))")
    task = ground(parsed, problem)
    facts, fluents = set(), set()
    for op in (*task.actions, *task.events):
        _indices(op.precondition, facts, fluents)
        _effect_indices(op.effect, facts, fluents)
    for proc in task.processes:
        _indices(proc.precondition, facts, fluents)
        for c in proc.continuous:
            fluents.add(c.fluent)
            _indices(tk.Comparison("=", c.rate, c.rate), facts, fluents)
    _indices(task.goal, facts, fluents)
    # every index the operators use names a fact/fluent of the task; no constant is left over
    assert facts <= set(range(len(task.facts)))
    assert fluents <= set(range(len(task.fluents)))
    assert len(task.init_values) == len(task.fluents)


def _num(e: tk.NumExpr, fluents: set[int]) -> None:
    if isinstance(e, tk.FluentRef):
        fluents.add(e.index)
    elif isinstance(e, tk.BinOp):
        _num(e.left, fluents)
        _num(e.right, fluents)
    elif isinstance(e, tk.Neg):
        _num(e.operand, fluents)


def _indices(c: tk.Condition, facts: set[int], fluents: set[int]) -> None:
    if isinstance(c, tk.Atom):
        facts.add(c.fact)
    elif isinstance(c, tk.And | tk.Or):
        assert len(c.parts) >= 2  # simplified: no empty or single-part connectives
        for p in c.parts:
            assert not isinstance(p, tk.Truth)
            _indices(p, facts, fluents)
    elif isinstance(c, tk.Not):
        assert not isinstance(c.operand, tk.Truth | tk.Not)
        _indices(c.operand, facts, fluents)
    elif isinstance(c, tk.Comparison):
        _num(c.left, fluents)
        _num(c.right, fluents)


def _effect_indices(e: tk.Effect, facts: set[int], fluents: set[int]) -> None:
    facts.update(e.add)
    facts.update(e.delete)
    for n in e.numeric:
        fluents.add(n.fluent)
        _num(n.expr, fluents)
    for ce in e.conditional:
        assert not isinstance(ce.condition, tk.Truth)
        _indices(ce.condition, facts, fluents)
        _effect_indices(ce.effect, facts, fluents)
