"""Relaxed reachability: which ground operators could ever apply, which facts could ever hold.

Delete effects are ignored, negated conditions and numeric comparisons are assumed satisfiable
(optimistic), so an operator pruned here can never apply in any real execution.
"""

from __future__ import annotations

from collections.abc import Sequence

from artiplan.pddl import task as t
from artiplan.pddl.operators import Instance


def relaxed_holds(c: t.Condition, reached: set[int]) -> bool:
    """Could ``c`` hold in some state whose true facts are among ``reached``?"""
    if isinstance(c, t.Atom):
        return c.fact in reached
    if isinstance(c, t.And):
        return all(relaxed_holds(p, reached) for p in c.parts)
    if isinstance(c, t.Or):
        return any(relaxed_holds(p, reached) for p in c.parts)
    if isinstance(c, t.Truth):
        return c.value
    return True  # negations and numeric comparisons: optimistic


def _adds(effect: t.Effect, reached: set[int]) -> list[int]:
    out = list(effect.add)
    for ce in effect.conditional:
        if relaxed_holds(ce.condition, reached):
            out.extend(_adds(ce.effect, reached))
    return out


def reachable(
    instances: Sequence[Instance], init: set[int]
) -> tuple[list[bool], set[int]]:
    """Which instances are relaxed-applicable, and the facts that can become true."""
    reached = set(init)
    applicable = [False] * len(instances)
    effects = [inst.effect.effect() for inst in instances]
    changed = True
    while changed:
        changed = False
        for i, inst in enumerate(instances):
            if not applicable[i]:
                if not relaxed_holds(inst.precondition, reached):
                    continue
                applicable[i] = True
                changed = True
            new = [f for f in _adds(effects[i], reached) if f not in reached]
            if new:
                reached.update(new)
                changed = True
    return applicable, reached
