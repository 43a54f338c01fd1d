"""States of a grounded PDDL+ task at one time point."""

from __future__ import annotations

import math
from dataclasses import dataclass

from artiplan.pddl.task import Task


@dataclass(frozen=True)
class State:
    """The world at time ``time`` [s]: the true facts and the value of every numeric fluent.

    ``values[i]`` is fluent ``i`` of the task; an undefined fluent is ``nan`` (comparisons that
    read it are false, as far as Python's float rules go; the validator reports it).
    """

    time: float
    facts: frozenset[int]
    values: tuple[float, ...]

    def key(self, precision: float = 1e-6) -> tuple[frozenset[int], tuple[int, ...]]:
        """A hashable key for duplicate detection: the facts and the values rounded to
        multiples of ``precision`` (time is not part of the key)."""
        return self.facts, tuple(
            round(v / precision) if math.isfinite(v) else 0 for v in self.values
        )

    def with_time(self, time: float) -> State:
        return State(time, self.facts, self.values)


def initial_state(task: Task) -> State:
    """The task's initial state at time 0 (events not yet fired: see ``settle``)."""
    values = tuple(math.nan if v is None else float(v) for v in task.init_values)
    return State(0.0, frozenset(task.init_facts), values)
