"""When two actions at (nearly) the same time interfere: PDDL 2.1 mutex, as VAL checks it."""

from __future__ import annotations

from artiplan.pddl.task import Effect, GroundAction
from artiplan.records import dataclass
from artiplan.semantics.walks import condition_parts, fluents_of


@dataclass(frozen=True)
class Footprint:
    """What an action reads and writes (conditional effects included, conservatively)."""

    read_facts: frozenset[int]
    read_fluents: frozenset[int]
    adds: frozenset[int]
    deletes: frozenset[int]
    additive: frozenset[int]  # fluents only increased / decreased
    assigned: frozenset[int]  # fluents assigned or scaled


def footprint(action: GroundAction) -> Footprint:
    """The read and write sets of ``action``."""
    rf, rn, _ = condition_parts(action.precondition)
    adds: set[int] = set()
    dels: set[int] = set()
    additive: set[int] = set()
    assigned: set[int] = set()
    stack: list[Effect] = [action.effect]
    while stack:
        e = stack.pop()
        adds.update(e.add)
        dels.update(e.delete)
        for ne in e.numeric:
            rn |= fluents_of(ne.expr)
            (additive if ne.op in ("increase", "decrease") else assigned).add(ne.fluent)
            if ne.op not in ("increase", "decrease", "assign"):
                rn.add(ne.fluent)  # scaling reads the old value
        for ce in e.conditional:
            f, n, _ = condition_parts(ce.condition)
            rf |= f
            rn |= n
            stack.append(ce.effect)
    return Footprint(frozenset(rf), frozenset(rn), frozenset(adds), frozenset(dels),
                     frozenset(additive - assigned), frozenset(assigned))


def interferes(a: GroundAction, b: GroundAction) -> bool:
    """True when ``a`` and ``b`` may not happen at the same time (see ``validator``)."""
    fa, fb = footprint(a), footprint(b)
    return _one_way(fa, fb) or _one_way(fb, fa)


def _one_way(x: Footprint, y: Footprint) -> bool:
    writes_facts = x.adds | x.deletes
    writes_fluents = x.additive | x.assigned
    return bool(
        writes_facts & y.read_facts
        or x.adds & y.deletes
        or writes_fluents & y.read_fluents
        or x.assigned & (y.additive | y.assigned)
    )
