"""Smart constructors that fold constants while building indexed conditions and expressions."""

from __future__ import annotations

import operator
from collections.abc import Callable, Iterable

from artiplan.pddl import task as t

_ARITH: dict[str, Callable[[float, float], float]] = {
    "+": operator.add,
    "-": operator.sub,
    "*": operator.mul,
    "/": operator.truediv,
    "^": operator.pow,
}

_COMPARE: dict[str, Callable[[float, float], bool]] = {
    "<": operator.lt,
    "<=": operator.le,
    ">": operator.gt,
    ">=": operator.ge,
    "=": operator.eq,
}


def make_and(parts: Iterable[t.Condition]) -> t.Condition:
    """``And`` without ``TRUE`` parts, flattened; ``FALSE`` if any part is ``FALSE``."""
    return _junction(parts, t.And, absorbing=False)


def make_or(parts: Iterable[t.Condition]) -> t.Condition:
    """``Or`` without ``FALSE`` parts, flattened; ``TRUE`` if any part is ``TRUE``."""
    return _junction(parts, t.Or, absorbing=True)


def _junction(
    parts: Iterable[t.Condition], kind: type[t.And] | type[t.Or], absorbing: bool
) -> t.Condition:
    """A flattened, duplicate-free ``kind`` of ``parts``: a constant equal to ``absorbing``
    decides the whole, the other constant drops out (and is the value of an empty one)."""
    decided, neutral = (t.TRUE, t.FALSE) if absorbing else (t.FALSE, t.TRUE)
    out: list[t.Condition] = []
    for p in parts:
        if isinstance(p, t.Truth):
            if p.value == absorbing:
                return decided
            continue
        if isinstance(p, kind):
            out.extend(p.parts)
        else:
            out.append(p)
    out = list(dict.fromkeys(out))
    if not out:
        return neutral
    return out[0] if len(out) == 1 else kind(tuple(out))


def make_not(c: t.Condition) -> t.Condition:
    """``Not``, folding truth values and double negation."""
    if isinstance(c, t.Truth):
        return t.Truth(not c.value)
    if isinstance(c, t.Not):
        return c.operand
    return t.Not(c)


def make_arith(op: str, left: t.NumExpr, right: t.NumExpr) -> t.NumExpr:
    """``BinOp``, or a ``Const`` when both sides are constant (never divides by zero)."""
    if (isinstance(left, t.Const) and isinstance(right, t.Const)
            and not (op == "/" and right.value == 0)
            and not (op == "^" and left.value < 0 and not float(right.value).is_integer())):
        return t.Const(_ARITH[op](left.value, right.value))
    return t.BinOp(op, left, right)  # type: ignore[arg-type]


def make_compare(op: str, left: t.NumExpr, right: t.NumExpr) -> t.Condition:
    """``Comparison``, or a ``Truth`` when both sides are constant."""
    if isinstance(left, t.Const) and isinstance(right, t.Const):
        return t.Truth(_COMPARE[op](left.value, right.value))
    return t.Comparison(op, left, right)  # type: ignore[arg-type]
