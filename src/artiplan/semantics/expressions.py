"""Evaluating numeric expressions and conditions, slowly (tree walk) or fast (compiled).

Comparisons can be read with tolerances (:class:`Tolerances`): exact mathematics by default,
VAL's reading in the validator (:data:`VAL_TOLERANCES`):

* ``l > r``  holds iff ``l - r > -strict_slack``   (``<`` symmetric);
* ``l >= r`` holds iff ``l - r >= -eps``           (``<=`` symmetric);
* ``l = r``  holds iff ``|l - r| <= eps``.

``eps`` only absorbs floating-point rounding (a value computed as 359.99999999999994 where the
mathematics says 360); ``strict_slack`` is VAL's slack on strict comparisons (shared/docs/stack.md:
VAL reads ``x > c`` as ``x - c > -0.0001``).

Compiled forms are generated Python lambdas (``compile_expr``, ``compile_condition``): about ten
times faster than walking the tree, which matters to the planner.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass

from artiplan.pddl.task import (
    And,
    Atom,
    BinOp,
    Comparison,
    Condition,
    Const,
    FluentRef,
    Neg,
    Not,
    NumExpr,
    Or,
    Task,
    Truth,
)
from artiplan.semantics.state import State
from artiplan.tolerances import VAL_SLACK

ExprFn = Callable[[Sequence[float]], float]
CondFn = Callable[[Collection[int], Sequence[float]], bool]


@dataclass(frozen=True)
class Tolerances:
    """How comparisons are read (module docstring). Units: those of the compared values."""

    strict_slack: float = 0.0
    eps: float = 0.0


EXACT = Tolerances()
#: VAL's reading (measured, :mod:`artiplan.tolerances`): slack 1e-4 on every comparison.
VAL_TOLERANCES = Tolerances(strict_slack=VAL_SLACK, eps=VAL_SLACK)


# ------------------------------------------------------------------------------ tree walking


def evaluate(expr: NumExpr, values: Sequence[float]) -> float:
    """Value of ``expr`` given fluent ``values`` (division by zero raises ZeroDivisionError)."""
    if isinstance(expr, Const):
        return expr.value
    if isinstance(expr, FluentRef):
        return values[expr.index]
    if isinstance(expr, Neg):
        return -evaluate(expr.operand, values)
    a = evaluate(expr.left, values)
    b = evaluate(expr.right, values)
    if expr.op == "+":
        return a + b
    if expr.op == "-":
        return a - b
    if expr.op == "*":
        return a * b
    return a / b


def compare(op: str, diff: float, tol: Tolerances = EXACT) -> bool:
    """Truth of ``left op right`` given ``diff = left - right``."""
    if op == ">":
        return diff > -tol.strict_slack
    if op == "<":
        return diff < tol.strict_slack
    if op == ">=":
        return diff >= -tol.eps
    if op == "<=":
        return diff <= tol.eps
    return abs(diff) <= tol.eps


def holds_values(
    cond: Condition, facts: Collection[int], values: Sequence[float], tol: Tolerances = EXACT
) -> bool:
    """Truth of ``cond`` for the given facts and values (tree walk)."""
    if isinstance(cond, Atom):
        return cond.fact in facts
    if isinstance(cond, Comparison):
        diff = evaluate(cond.left, values) - evaluate(cond.right, values)
        return compare(cond.op, diff, tol)
    if isinstance(cond, And):
        return all(holds_values(p, facts, values, tol) for p in cond.parts)
    if isinstance(cond, Or):
        return any(holds_values(p, facts, values, tol) for p in cond.parts)
    if isinstance(cond, Not):
        return not holds_values(cond.operand, facts, values, tol)
    return cond.value


def robustness(cond: Condition, facts: Collection[int], values: Sequence[float]) -> float:
    """How far ``cond`` is from changing truth value, in the units of its comparisons.

    Positive when it holds (the least change of a compared difference that would make it
    false), negative when it does not (minus the least change that would make it true);
    facts and constants count as +-inf. ``And`` takes the minimum, ``Or`` the maximum.
    """
    if isinstance(cond, Atom):
        return math.inf if cond.fact in facts else -math.inf
    if isinstance(cond, Truth):
        return math.inf if cond.value else -math.inf
    if isinstance(cond, Not):
        return -robustness(cond.operand, facts, values)
    if isinstance(cond, And | Or):
        parts = [robustness(p, facts, values) for p in cond.parts]
        if not parts:
            return math.inf if isinstance(cond, And) else -math.inf
        return min(parts) if isinstance(cond, And) else max(parts)
    d = evaluate(cond.left, values) - evaluate(cond.right, values)
    return {">": d, ">=": d, "<": -d, "<=": -d}.get(cond.op, -abs(d))


def holds(cond: Condition, state: State, tol: Tolerances = EXACT) -> bool:
    """Truth of ``cond`` in ``state``."""
    return holds_values(cond, state.facts, state.values, tol)


# -------------------------------------------------------------------------------- compiling


def expr_source(expr: NumExpr, var: str = "v") -> str:
    """Python source of a numeric expression over the sequence named ``var`` (for compiling)."""
    if isinstance(expr, Const):
        return repr(float(expr.value))
    if isinstance(expr, FluentRef):
        return f"{var}[{expr.index}]"
    if isinstance(expr, Neg):
        return f"(-{expr_source(expr.operand, var)})"
    return f"({expr_source(expr.left, var)} {expr.op} {expr_source(expr.right, var)})"


def _cond_src(cond: Condition, tol: Tolerances) -> str:
    if isinstance(cond, Atom):
        return f"({cond.fact} in f)"
    if isinstance(cond, Truth):
        return "True" if cond.value else "False"
    if isinstance(cond, Not):
        return f"(not {_cond_src(cond.operand, tol)})"
    if isinstance(cond, And | Or):
        if not cond.parts:
            return "True" if isinstance(cond, And) else "False"
        joiner = " and " if isinstance(cond, And) else " or "
        return "(" + joiner.join(_cond_src(p, tol) for p in cond.parts) + ")"
    diff = f"({expr_source(cond.left)} - {expr_source(cond.right)})"
    bound = {">": -tol.strict_slack, "<": tol.strict_slack, ">=": -tol.eps, "<=": tol.eps}
    if cond.op == "=":
        return f"(abs{diff} <= {tol.eps!r})"
    return f"({diff} {cond.op} {float(bound[cond.op])!r})"


def compile_expr(expr: NumExpr) -> ExprFn:
    """``expr`` as a fast function of the fluent values."""
    try:
        return eval(f"lambda v: {expr_source(expr)}", {})
    except (RecursionError, SyntaxError, MemoryError):  # pathological depth: walk the tree
        return lambda v: evaluate(expr, v)


def compile_condition(cond: Condition, tol: Tolerances = EXACT) -> CondFn:
    """``cond`` as a fast function ``(facts, values) -> bool`` (read with ``tol``)."""
    try:
        return eval(f"lambda f, v: {_cond_src(cond, tol)}", {})
    except (RecursionError, SyntaxError, MemoryError):
        return lambda f, v: holds_values(cond, f, v, tol)


def compile_near(cond: Condition, zero_tol: float) -> ExprFn:
    """A fast test ``values -> bool``: is any comparison of ``cond`` within ``zero_tol`` of its
    boundary? (Returns a float-compatible bool; False when ``cond`` has no comparison.)"""
    comps = condition_parts(cond)[2]
    if not comps:
        return lambda v: False
    terms = " or ".join(
        f"abs({expr_source(c.left)} - {expr_source(c.right)}) <= {zero_tol!r}" for c in comps
    )
    try:
        return eval(f"lambda v: {terms}", {})
    except (RecursionError, SyntaxError, MemoryError):
        return lambda v: any(
            abs(evaluate(c.left, v) - evaluate(c.right, v)) <= zero_tol for c in comps
        )


# ---------------------------------------------------------------------------- introspection


def expr_fluents(expr: NumExpr, out: set[int] | None = None) -> set[int]:
    """The fluents ``expr`` reads."""
    out = set() if out is None else out
    if isinstance(expr, FluentRef):
        out.add(expr.index)
    elif isinstance(expr, Neg):
        expr_fluents(expr.operand, out)
    elif isinstance(expr, BinOp):
        expr_fluents(expr.left, out)
        expr_fluents(expr.right, out)
    return out


def condition_parts(cond: Condition) -> tuple[set[int], set[int], list[Comparison]]:
    """(facts read, fluents read, comparisons) of ``cond``."""
    facts: set[int] = set()
    fluents: set[int] = set()
    comps: list[Comparison] = []
    stack = [cond]
    while stack:
        c = stack.pop()
        if isinstance(c, Atom):
            facts.add(c.fact)
        elif isinstance(c, Comparison):
            comps.append(c)
            expr_fluents(c.left, fluents)
            expr_fluents(c.right, fluents)
        elif isinstance(c, And | Or):
            stack.extend(c.parts)
        elif isinstance(c, Not):
            stack.append(c.operand)
    return facts, fluents, comps


# ---------------------------------------------------------------------------------- printing


def format_expr(expr: NumExpr, task: Task | None = None) -> str:
    """PDDL text of ``expr``; fluents by name when ``task`` is given."""
    if isinstance(expr, Const):
        v = expr.value
        return repr(int(v)) if float(v).is_integer() and abs(v) < 1e15 else repr(v)
    if isinstance(expr, FluentRef):
        return task.fluents[expr.index] if task else f"(fluent#{expr.index})"
    if isinstance(expr, Neg):
        return f"(- {format_expr(expr.operand, task)})"
    return f"({expr.op} {format_expr(expr.left, task)} {format_expr(expr.right, task)})"


def format_condition(cond: Condition, task: Task | None = None) -> str:
    """PDDL text of ``cond``; facts and fluents by name when ``task`` is given."""
    if isinstance(cond, Atom):
        return task.facts[cond.fact] if task else f"(fact#{cond.fact})"
    if isinstance(cond, Truth):
        return "(and)" if cond.value else "(or)"
    if isinstance(cond, Not):
        return f"(not {format_condition(cond.operand, task)})"
    if isinstance(cond, And | Or):
        word = "and" if isinstance(cond, And) else "or"
        return f"({word} " + " ".join(format_condition(p, task) for p in cond.parts) + ")"
    return f"({cond.op} {format_expr(cond.left, task)} {format_expr(cond.right, task)})"


def unsatisfied_parts(
    cond: Condition, facts: Collection[int], values: Sequence[float], tol: Tolerances = EXACT
) -> list[Condition]:
    """The smallest false parts of a false ``cond`` (conjuncts descended), for error messages."""
    if holds_values(cond, facts, values, tol):
        return []
    if isinstance(cond, And):
        out: list[Condition] = []
        for p in cond.parts:
            out.extend(unsatisfied_parts(p, facts, values, tol))
        return out
    return [cond]


def fluent_values(cond: Condition, task: Task, values: Sequence[float]) -> dict[str, float]:
    """Name -> value of every fluent ``cond`` reads (for error messages)."""
    _, fluents, _ = condition_parts(cond)
    return {task.fluents[i]: values[i] for i in sorted(fluents)}


def is_finite(values: Sequence[float]) -> bool:
    return all(math.isfinite(v) for v in values)
