"""A state of a grounded PDDL+ task at one time point."""

from __future__ import annotations

from artiplan.records import dataclass


@dataclass(frozen=True)
class State:
    """The world at time ``time`` [s]: the true facts as a bit mask (fact ``i`` true iff bit
    ``i`` is set) and the value of every numeric fluent (``nan`` where undefined)."""

    time: float
    facts: int
    values: tuple[float, ...]

    def holds_fact(self, fact: int) -> bool:
        """True when fact ``fact`` is true."""
        return bool(self.facts >> fact & 1)
