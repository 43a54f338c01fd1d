"""Timed plans: what planners produce, validators check and the robot executes.

A contract shared by ``semantics`` (reading, writing, validating), ``search`` and ``backends``
(producing) and ``execution`` (dispatching). Reading and writing files: :mod:`plan_io`.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass(frozen=True)
class TimedAction:
    """An action started at ``time`` [s]; ``duration`` only for durative actions (``[d]``)."""

    time: float
    name: str
    args: tuple[str, ...] = ()
    duration: float | None = None
    #: Line of the plan file it came from (for messages); not part of equality.
    line: int | None = field(default=None, compare=False)

    @property
    def signature(self) -> str:
        return "(" + " ".join((self.name, *self.args)) + ")"


@dataclass(frozen=True)
class TimedEvent:
    """An event a simulator predicts at ``time`` [s]; printed as a ``;`` comment line."""

    time: float
    name: str
    args: tuple[str, ...] = ()
    #: True when the actions of the same instant triggered it (it is printed after them).
    after_actions: bool = field(default=False, compare=False)

    @property
    def signature(self) -> str:
        return "(" + " ".join((self.name, *self.args)) + ")"


@dataclass(frozen=True)
class Plan:
    """Actions in time order, plus (optionally) the events predicted between them.

    ``end`` [s]: an explicit end of the plan (ENHSP's ``T: @PlanEND``, or the end of its last
    ``-----waiting----``); the validator checks the goal there, as if a no-op action happened
    at ``end`` (VAL has no such marker: write an ``observe`` action instead).
    """

    actions: tuple[TimedAction, ...]
    events: tuple[TimedEvent, ...] = field(default=())
    end: float | None = None

    @property
    def makespan(self) -> float:
        """Time of the last happening (or of ``end``) [s] (0 for an empty plan)."""
        last = max((a.time + (a.duration or 0.0) for a in self.actions), default=0.0)
        return last if self.end is None else max(last, self.end)

    def __len__(self) -> int:
        return len(self.actions)
