"""The walks over a grounded task's expressions and conditions, written once for every stage.

Numeric expressions (:mod:`artiplan.pddl.task`): the fluents they read, their value, their
linear form, their polynomial in elapsed time along a flow, an interval enclosure, Python source
for compiling. Conditions: their parts, their truth with :class:`~artiplan.tolerances.Tolerances`
(facts as a bit mask), the truth with any rule for comparisons (right limits), robustness, the
false parts, printing. The validator, the planner, the heuristic and the proofs all use these.
"""

from __future__ import annotations

import functools
import math
import operator
from collections.abc import Callable, Sequence
from types import CodeType

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
from artiplan.semantics import polynomial as P
from artiplan.tolerances import VAL, Tolerances
from artiplan.typenames import Any

#: A linear form ``({fluent: coefficient}, constant)``.
Linear = tuple[dict[int, float], float]
#: An interval ``(lo, hi)``.
Box = tuple[float, float]

# ------------------------------------------------------------------------------------ reading


def fluents_of(expr: NumExpr) -> frozenset[int]:
    """The fluents ``expr`` reads."""
    if isinstance(expr, FluentRef):
        return frozenset((expr.index,))
    if isinstance(expr, Neg):
        return fluents_of(expr.operand)
    if isinstance(expr, BinOp):
        return fluents_of(expr.left) | fluents_of(expr.right)
    return frozenset()


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
            fluents |= fluents_of(c.left) | fluents_of(c.right)
        elif isinstance(c, And | Or):
            stack.extend(c.parts)
        elif isinstance(c, Not):
            stack.append(c.operand)
    return facts, fluents, comps


def conjuncts(cond: Condition) -> list[Condition]:
    """The parts of a (nested) top-level conjunction."""
    if isinstance(cond, And):
        return [c for part in cond.parts for c in conjuncts(part)]
    return [cond]


# ------------------------------------------------------------------------------------ values


class DomainError(ZeroDivisionError):
    """A value outside an operation's domain (a negative base to a fractional power): caught
    wherever a division by zero is, since both leave the expression undefined."""


#: A negative base this close to 0 is 0 to a fractional power (float rounding of a level that
#: drained to exactly 0, not a negative level).
POWER_ZERO = 1e-9


def power(a: float, b: float) -> float:
    """``a ^ b`` as PDDL reads it: real, undefined (DomainError) for a < 0 and fractional b
    (Python's ``**`` would return a complex number)."""
    if a < 0.0 and not float(b).is_integer():
        if a >= -POWER_ZERO:
            return 0.0 if b > 0 else math.inf  # rounding below a 0 the dynamics stop at
        raise DomainError(f"({a}) ^ {b} is not a real number")
    return float(a**b)


#: Names the generated sources (:func:`expr_source`) use, for their ``eval``.
SOURCE_GLOBALS: dict[str, object] = {"_pow": power}


@functools.lru_cache(maxsize=65536)
def _code(source: str, mode: str) -> CodeType:
    # Python's compile() is most of the cost of compiling a task, and the same sources come
    # back: the planner's and the validator's views of one task, every re-planning problem.
    return compile(source, "<artiplan-generated>", mode)


def source_function(source: str) -> Callable[..., Any]:
    """The function a generated ``lambda ...: ...`` expression ``source`` evaluates to."""
    fn: Callable[..., Any] = eval(_code(source, "eval"), dict(SOURCE_GLOBALS))  # noqa: S307 - source generated from the task
    return fn


def source_definitions(source: str) -> dict[str, Any]:
    """The names generated ``def`` statements ``source`` define (a fresh namespace)."""
    namespace: dict[str, Any] = dict(SOURCE_GLOBALS)
    exec(_code(source, "exec"), namespace)  # noqa: S102 - source generated from the task
    return namespace


#: The binary operators of numeric expressions (``^`` real: :func:`power`).
BINARY: dict[str, Callable[[float, float], float]] = {
    "+": operator.add, "-": operator.sub, "*": operator.mul, "/": operator.truediv, "^": power}


def evaluate(expr: NumExpr, values: Sequence[float]) -> float:
    """Value of ``expr`` (division by zero raises ZeroDivisionError)."""
    if isinstance(expr, Const):
        return expr.value
    if isinstance(expr, FluentRef):
        return values[expr.index]
    if isinstance(expr, Neg):
        return -evaluate(expr.operand, values)
    return BINARY[expr.op](evaluate(expr.left, values), evaluate(expr.right, values))


def truth(cond: Condition, facts: int, comparison: Callable[[Comparison], bool]) -> bool:
    """Truth of ``cond`` with fact bit mask ``facts`` and a rule for comparisons."""
    if isinstance(cond, Atom):
        return bool(facts >> cond.fact & 1)
    if isinstance(cond, Comparison):
        return comparison(cond)
    if isinstance(cond, And):
        return all(truth(p, facts, comparison) for p in cond.parts)
    if isinstance(cond, Or):
        return any(truth(p, facts, comparison) for p in cond.parts)
    if isinstance(cond, Not):
        return not truth(cond.operand, facts, comparison)
    assert isinstance(cond, Truth)
    return cond.value


def holds(cond: Condition, facts: int, values: Sequence[float], tol: Tolerances = VAL) -> bool:
    """Truth of ``cond`` at a time point, comparisons read with ``tol``."""
    return truth(cond, facts, lambda c: tol.point(c.op, evaluate(c.left, values)
                                                  - evaluate(c.right, values)))


def robustness(cond: Condition, facts: int, values: Sequence[float]) -> float:
    """How far ``cond`` is from changing truth value, in the units of its comparisons.

    Positive when it holds (the least change of a compared difference that would make it
    false), negative when it does not; facts and constants count as +-inf. ``And`` takes the
    minimum, ``Or`` the maximum.
    """
    if isinstance(cond, Atom):
        return math.inf if facts >> cond.fact & 1 else -math.inf
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


def unsatisfied_parts(
    cond: Condition, facts: int, values: Sequence[float], tol: Tolerances = VAL
) -> list[Condition]:
    """The smallest false parts of a false ``cond`` (conjuncts descended), for messages."""
    if holds(cond, facts, values, tol):
        return []
    if isinstance(cond, And):
        return [q for p in cond.parts for q in unsatisfied_parts(p, facts, values, tol)]
    return [cond]


# ------------------------------------------------------------------------- forms of expressions


def linear(expr: NumExpr) -> Linear | None:
    """``expr`` as ``sum a_i v_i + b``, or None if it is not linear in the fluents."""
    if isinstance(expr, Const):
        return {}, float(expr.value)
    if isinstance(expr, FluentRef):
        return {expr.index: 1.0}, 0.0
    if isinstance(expr, Neg):
        inner = linear(expr.operand)
        return None if inner is None else ({k: -a for k, a in inner[0].items()}, -inner[1])
    left, right = linear(expr.left), linear(expr.right)
    if left is None or right is None:
        return None
    if expr.op in "+-":
        sign = 1.0 if expr.op == "+" else -1.0
        coeffs = dict(left[0])
        for k, a in right[0].items():
            coeffs[k] = coeffs.get(k, 0.0) + sign * a
        return {k: a for k, a in coeffs.items() if a != 0.0}, left[1] + sign * right[1]
    if expr.op == "*" and not (left[0] and right[0]):
        scale, (coeffs, const) = (left[1], right) if not left[0] else (right[1], left)
        return {f: scale * a for f, a in coeffs.items() if scale * a != 0.0}, scale * const
    if expr.op == "/" and not right[0] and right[1] != 0.0:
        return {k: a / right[1] for k, a in left[0].items()}, left[1] / right[1]
    if expr.op == "^" and not left[0] and not right[0]:
        return {}, float(left[1] ** right[1])
    return None


def linear_difference(comp: Comparison) -> Linear | None:
    """``left - right`` of ``comp`` as :func:`linear` reads it (None if not linear)."""
    return linear(BinOp("-", comp.left, comp.right))


def to_poly(expr: NumExpr, poly_of: Callable[[int], P.Poly | None]) -> P.Poly | None:
    """``expr`` as a polynomial in elapsed time given each fluent's (``poly_of``); None when
    it is not one (a quotient by a changing value, a fractional power of one)."""
    if isinstance(expr, Const):
        return (float(expr.value),)
    if isinstance(expr, FluentRef):
        return poly_of(expr.index)
    if isinstance(expr, Neg):
        inner = to_poly(expr.operand, poly_of)
        return None if inner is None else P.neg(inner)
    a, b = to_poly(expr.left, poly_of), to_poly(expr.right, poly_of)
    if a is None or b is None:
        return None
    if expr.op == "+":
        return P.add(a, b)
    if expr.op == "-":
        return P.sub(a, b)
    if expr.op == "*":
        return P.mul(a, b)
    if expr.op == "/":
        return P.scale(a, 1.0 / b[0]) if len(b) == 1 and b[0] != 0.0 else None
    if len(b) == 1 and float(b[0]).is_integer() and 0 <= b[0] <= 8:
        out: P.Poly = (1.0,)
        for _ in range(int(b[0])):
            out = P.mul(out, a)
        return out
    return (a[0] ** b[0],) if len(a) == 1 and len(b) == 1 else None


def interval(expr: NumExpr, box: Callable[[int], Box]) -> Box:
    """An enclosure of ``expr`` when every fluent ``i`` lies in ``box(i)`` (interval
    arithmetic; a division by an interval holding 0, or an undefined power, gives (-inf, inf))."""
    if isinstance(expr, Const):
        return expr.value, expr.value
    if isinstance(expr, FluentRef):
        return box(expr.index)
    if isinstance(expr, Neg):
        lo, hi = interval(expr.operand, box)
        return -hi, -lo
    (a, b), (c, d) = interval(expr.left, box), interval(expr.right, box)
    if expr.op == "+":
        return a + c, b + d
    if expr.op == "-":
        return a - d, b - c
    if expr.op == "*":
        ends = [a * c, a * d, b * c, b * d]
        ends = [0.0 if math.isnan(x) else x for x in ends]
        return min(ends), max(ends)
    if expr.op == "/":
        if c <= 0.0 <= d:
            return -math.inf, math.inf
        ends = [a / c, a / d, b / c, b / d]
        return min(ends), max(ends)
    return _power(a, b, c, d)


def _power(a: float, b: float, c: float, d: float) -> Box:
    """Enclosure of x ** y for x in [a, b], y in [c, d] (y constant, or x >= 0)."""
    if c == d and float(c).is_integer():
        n = int(c)
        ends = [_int_power(a, n), _int_power(b, n)] if a != 0.0 or n >= 0 else \
            [-math.inf, math.inf]
        lo, hi = min(ends), max(ends)
        if n % 2 == 0 and n > 0 and a < 0.0 < b:
            lo = 0.0
        return lo, hi
    if a < 0.0:
        return -math.inf, math.inf
    try:
        ends = [x**y for x in (a, b) for y in (c, d)]
    except (OverflowError, ZeroDivisionError):
        return -math.inf, math.inf
    return min(ends), max(ends)


def _int_power(x: float, n: int) -> float:
    """``x ** n`` for an integer ``n``, +-inf where the float overflows (an enclosure of a
    numeric flow that diverges)."""
    try:
        return x**n
    except OverflowError:
        return math.copysign(math.inf, x) if n % 2 else math.inf


# ----------------------------------------------------------------------------------- compiling


def expr_source(expr: NumExpr, var: str = "V") -> str:
    """Python source of ``expr`` over the sequence named ``var``."""
    if isinstance(expr, Const):
        return repr(float(expr.value))
    if isinstance(expr, FluentRef):
        return f"{var}[{expr.index}]"
    if isinstance(expr, Neg):
        return f"(-{expr_source(expr.operand, var)})"
    if expr.op == "^":
        return f"_pow({expr_source(expr.left, var)}, {expr_source(expr.right, var)})"
    return f"({expr_source(expr.left, var)} {expr.op} {expr_source(expr.right, var)})"


def condition_source(cond: Condition, comparison: Callable[[Comparison], str]) -> str:
    """Python source of ``cond`` over ``F`` (fact bit mask), comparisons from ``comparison``."""
    if isinstance(cond, Truth):
        return "True" if cond.value else "False"
    if isinstance(cond, Atom):
        return f"(F & {1 << cond.fact} != 0)"
    if isinstance(cond, Not):
        return f"(not {condition_source(cond.operand, comparison)})"
    if isinstance(cond, And | Or):
        if not cond.parts:
            return "True" if isinstance(cond, And) else "False"
        glue = " and " if isinstance(cond, And) else " or "
        return "(" + glue.join(condition_source(p, comparison) for p in cond.parts) + ")"
    assert isinstance(cond, Comparison)
    return comparison(cond)


def comparison_source(cond: Comparison, tol: Tolerances) -> str:
    """Python source of one comparison read at a time point with ``tol``."""
    left, right = expr_source(cond.left), expr_source(cond.right)
    if cond.op == "=":
        return f"(abs({left} - {right}) <= {tol.slack!r})"
    return f"({left} - {right} + {tol.offset(cond.op)!r} {cond.op} 0.0)"


# ------------------------------------------------------------------------------------ printing


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


def fluent_values(cond: Condition, task: Task, values: Sequence[float]) -> dict[str, float]:
    """Name -> value of every fluent ``cond`` reads (for messages)."""
    return {task.fluents[i]: values[i] for i in sorted(condition_parts(cond)[1])}
