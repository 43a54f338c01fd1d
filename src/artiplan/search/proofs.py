"""Proofs of unsolvability by a relaxed reachability and interval analysis.

Sound over-approximation of everything any plan can reach:

- fact literals: from the initial state, every action, event and process whose top-level fact
  literals are reachable adds its effects (deletes make the negative literal reachable); numeric
  preconditions are ignored (assumed satisfiable);
- fluents: intervals, by a fixpoint (:func:`fluent_bounds`): a fluent no reachable happening or
  process changes keeps its initial value; one that processes only increase (decrease) keeps its
  initial value as a lower (upper) bound; constant assignments widen the interval to the constant.

The goal is then evaluated three-valued on these sets; if it cannot be true, no plan exists.
"""

from __future__ import annotations

import math

from artiplan.pddl.task import (
    And,
    Atom,
    Comparison,
    Condition,
    Effect,
    Not,
    NumericEffect,
    Or,
    Task,
    Truth,
)
from artiplan.semantics.compiled import fact_literals
from artiplan.semantics.walks import fluents_of, linear, linear_difference

Interval = tuple[float, float]


def _reachable_literals(task: Task) -> tuple[set[int], set[int], set[int]]:
    """(facts that can be true, facts that can be false, reachable process indices)."""
    n = len(task.facts)
    pos = set(task.init_facts)
    neg = set(range(n)) - pos
    ops = list(task.actions) + list(task.events)
    fired: set[int] = set()
    procs: set[int] = set()
    changed = True
    while changed:
        changed = False
        for i, op in enumerate(ops):
            if i in fired or not _enabled(op.precondition, pos, neg):
                continue
            fired.add(i)
            changed = True
            eff = op.effect
            pos.update(eff.add)
            neg.update(eff.delete)
            for ce in eff.conditional:
                pos.update(ce.effect.add)
                neg.update(ce.effect.delete)
        for i, proc in enumerate(task.processes):
            if i not in procs and _enabled(proc.precondition, pos, neg):
                procs.add(i)
                pos.update(proc.discrete.add)
                changed = True
    return pos, neg, procs


def _enabled(cond: Condition, pos: set[int], neg: set[int]) -> bool:
    lits = fact_literals(cond)
    if lits is None:
        return False
    req, forb = lits
    return all(i in pos for i in range(req.bit_length()) if req >> i & 1) and \
        all(i in neg for i in range(forb.bit_length()) if forb >> i & 1)


def fluent_bounds(task: Task) -> tuple[list[Interval], set[int], set[int]]:
    """Reachable interval of every fluent, and the reachable facts (true, false).

    A fixpoint: a process, action or event counts once its fact literals are reachable and its
    numeric precondition can hold within the bounds found so far. Assigning a constant widens
    the interval to include it; any other numeric effect, or a process, opens it in the
    direction it can move.
    """
    pos, neg, procs = _reachable_literals(task)
    bounds: list[Interval] = [
        (-math.inf, math.inf) if v is None else (v, v) for v in task.init_values
    ]
    ops = [op for op in list(task.actions) + list(task.events)
           if _enabled(op.precondition, pos, neg)]
    changed = True
    while changed:
        changed = False
        for i in sorted(procs):
            proc = task.processes[i]
            if True not in _possible(proc.precondition, bounds, pos, neg):
                continue
            for ce in proc.continuous:
                lin = linear(ce.rate)
                sign = (lin[1] > 0) - (lin[1] < 0) if lin is not None and not lin[0] else 2
                changed |= _widen(bounds, ce.fluent, sign)
        for op in ops:
            if True not in _possible(op.precondition, bounds, pos, neg):
                continue
            for ne in _numeric_effects(op.effect):
                lin = linear(ne.expr)
                const = lin[1] if lin is not None and not lin[0] else None
                if ne.op == "assign" and const is not None:
                    lo, hi = bounds[ne.fluent]
                    if not lo <= const <= hi:
                        bounds[ne.fluent] = (min(lo, const), max(hi, const))
                        changed = True
                elif ne.op in ("increase", "decrease") and const is not None:
                    up = (const > 0) == (ne.op == "increase")
                    changed |= _widen(bounds, ne.fluent, 1 if up else -1) if const else False
                else:
                    changed |= _widen(bounds, ne.fluent, 2)
    return bounds, pos, neg


def _numeric_effects(eff: Effect) -> list[NumericEffect]:
    out = list(eff.numeric)
    for ce in eff.conditional:
        out.extend(_numeric_effects(ce.effect))
    return out


def _widen(bounds: list[Interval], f: int, sign: int) -> bool:
    """Open fluent ``f``'s interval upwards (1), downwards (-1) or both (2); True if changed."""
    lo, hi = bounds[f]
    new = (-math.inf if sign in (-1, 2) else lo, math.inf if sign in (1, 2) else hi)
    bounds[f] = new
    return new != (lo, hi)


def _possible(cond: Condition, b: list[Interval], pos: set[int], neg: set[int]) -> set[bool]:
    """The truth values ``cond`` can take somewhere in the over-approximation."""
    if isinstance(cond, Truth):
        return {cond.value}
    if isinstance(cond, Atom):
        return ({True} if cond.fact in pos else set()) | ({False} if cond.fact in neg else set())
    if isinstance(cond, Not):
        return {not v for v in _possible(cond.operand, b, pos, neg)}
    if isinstance(cond, (And, Or)):
        # And: true if every part can be, false if one can; Or: the dual
        parts = [_possible(p, b, pos, neg) for p in cond.parts]
        every, one = (True, False) if isinstance(cond, And) else (False, True)
        out = {one} if any(one in p for p in parts) else set()
        return out | {every} if all(every in p for p in parts) else out
    assert isinstance(cond, Comparison)
    return _comparison_possible(cond, b)


def _comparison_possible(cond: Comparison, b: list[Interval]) -> set[bool]:
    lin = linear_difference(cond)
    if lin is None:
        return {True, False}
    lo = hi = lin[1]
    for f, a in lin[0].items():
        flo, fhi = b[f]
        terms = (a * flo, a * fhi)
        lo += min(terms) if not math.isnan(min(terms)) else -math.inf
        hi += max(terms) if not math.isnan(max(terms)) else math.inf
    out = set()
    if cond.op in (">", ">="):
        if hi > 0 or (cond.op == ">=" and hi >= 0):
            out.add(True)
        if lo < 0 or (cond.op == ">" and lo <= 0):
            out.add(False)
    elif cond.op in ("<", "<="):
        if lo < 0 or (cond.op == "<=" and lo <= 0):
            out.add(True)
        if hi > 0 or (cond.op == "<" and hi >= 0):
            out.add(False)
    else:
        if lo <= 0 <= hi:
            out.add(True)
        if lo < hi or lo != 0:
            out.add(False)
    return out


def prove_unsolvable(task: Task) -> str | None:
    """A reason why no plan can exist, or ``None`` if the analysis finds none."""
    bounds, pos, neg = fluent_bounds(task)
    parts = task.goal.parts if isinstance(task.goal, And) else (task.goal,)
    for part in parts:
        if True not in _possible(part, bounds, pos, neg):
            return f"goal conjunct {_show(part, task)} can never hold (relaxed reachability)"
    if True not in _possible(task.goal, bounds, pos, neg):
        return "the goal can never hold (relaxed reachability)"
    return None


def _show(cond: Condition, task: Task) -> str:
    if isinstance(cond, Atom):
        return task.facts[cond.fact]
    if isinstance(cond, Comparison):
        names = sorted(task.fluents[f] for f in fluents_of(cond.left) | fluents_of(cond.right))
        return f"({cond.op} ...) on {', '.join(names)}"
    return type(cond).__name__.lower()
