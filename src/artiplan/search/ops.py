"""The search's operators: what leads from a node to its successors (see
:mod:`artiplan.search.engine`)."""

from __future__ import annotations

from artiplan.records import dataclass


@dataclass(frozen=True, slots=True)
class Apply:
    """Apply action ``action`` now (``epsilon`` after the previous one, ``event_gap`` after
    the last event)."""

    action: int


class Rescue(Apply):
    """Apply action ``action`` to save an invariant the running processes are about to
    break (:mod:`artiplan.search.invariants`): a plan cannot do without it, so it does not
    count in the search's ``g`` (``g_weight``)."""

    __slots__ = ()


@dataclass(frozen=True, slots=True)
class WaitNext:
    """Wait until just after the next time a watched condition may change."""


@dataclass(frozen=True, slots=True)
class WaitGroup:
    """Wait until goal group ``group`` holds (plus the goal margin)."""

    group: int


@dataclass(frozen=True, slots=True)
class WaitGoal:
    """Wait until the whole goal holds (plus the goal margin)."""


@dataclass(frozen=True, slots=True)
class WaitFor:
    """Wait until action ``action``'s precondition holds (its facts hold, a number does not
    yet: a durative action's end, a threshold)."""

    action: int


@dataclass(frozen=True, slots=True)
class WaitBefore:
    """Wait until just before a condition that holds now fails (an action's precondition,
    an invariant): the last moment to act (a duration's upper bound, a capacity)."""


@dataclass(frozen=True, slots=True)
class WaitDelta:
    """Wait until the next multiple of the search's ``delta`` [s]: a free choice of time that
    no condition marks (when to brake so that a car stops in a window)."""


@dataclass(frozen=True, slots=True)
class WaitHold:
    """Wait ``seconds`` [s]: as long as the heuristic's motion profile keeps the controls as
    they are (a car accelerating until it must cruise or brake), or until just before the
    running processes would break an invariant (:mod:`artiplan.search.invariants`)."""

    seconds: float


@dataclass(frozen=True, slots=True)
class Start:
    """How the initial node is reached."""


Op = Apply | WaitNext | WaitGroup | WaitGoal | WaitFor | WaitBefore | WaitDelta | WaitHold | Start
WAIT_NEXT, WAIT_GOAL, WAIT_BEFORE, WAIT_DELTA, START = (WaitNext(), WaitGoal(), WaitBefore(),
                                                       WaitDelta(), Start())


__all__ = ["START", "WAIT_BEFORE", "WAIT_DELTA", "WAIT_GOAL", "WAIT_NEXT", "Apply", "Op",
           "Rescue", "Start", "WaitBefore", "WaitDelta", "WaitFor", "WaitGoal", "WaitGroup",
           "WaitHold", "WaitNext"]
