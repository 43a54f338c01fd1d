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

    @property
    def signature(self) -> str:
        return "(" + " ".join((self.name, *self.args)) + ")"


@dataclass(frozen=True)
class Plan:
    """Actions in time order, plus (optionally) the events predicted between them."""

    actions: tuple[TimedAction, ...]
    events: tuple[TimedEvent, ...] = field(default=())

    @property
    def makespan(self) -> float:
        """Time of the last happening [s] (0 for an empty plan)."""
        return max((a.time + (a.duration or 0.0) for a in self.actions), default=0.0)

    def __len__(self) -> int:
        return len(self.actions)
