"""Timed plans: what planners produce, validators check and the robot executes.

A contract shared by ``semantics`` (reading, writing, validating), ``search`` and ``backends``
(producing) and ``execution`` (dispatching). Reading and writing files: :mod:`plan_io`.
"""

from __future__ import annotations

from artiplan.records import dataclass, field, replace


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


#: How a compiled durative action's start and end are named (``artiplan.pddl.durative``).
DURATIVE_START, DURATIVE_END = "@start", "@end"


def expand_durative(plan: Plan, durative: tuple[str, ...]) -> Plan:
    """``plan`` with every durative action ``t: (N args) [d]`` as its compiled start at ``t``
    and end at ``t + d`` (other lines unchanged). Raises ValueError for a durative action
    without a duration."""
    names = {n.lower(): n for n in durative}
    if not names:
        return plan
    out: list[TimedAction] = []
    for a in plan.actions:
        name = names.get(a.name.lower())
        if name is None:
            out.append(a)
            continue
        if a.duration is None:
            raise ValueError(f"durative action {a.signature} at {a.time:g} needs a duration "
                             "(t: (name args) [d])")
        out.append(TimedAction(a.time, name + DURATIVE_START, a.args, line=a.line))
        out.append(TimedAction(round(a.time + a.duration, 9), name + DURATIVE_END, a.args,
                               line=a.line))
    return Plan(tuple(sorted(out, key=lambda x: x.time)), plan.events, plan.end)


def fold_durative(plan: Plan, durative: tuple[str, ...]) -> Plan:
    """The inverse of :func:`expand_durative`: each compiled start with the next end of the
    same action and arguments as one line ``t: (N args) [d]``."""
    if not durative:
        return plan
    starts = {n.lower() + DURATIVE_START: n for n in durative}
    ends = {n.lower() + DURATIVE_END: n for n in durative}
    out: list[TimedAction] = []
    open_runs: dict[tuple[str, tuple[str, ...]], list[int]] = {}
    for a in sorted(plan.actions, key=lambda x: x.time):
        key = a.name.lower()
        if key in starts:
            name = starts[key]
            open_runs.setdefault((name, a.args), []).append(len(out))
            out.append(TimedAction(a.time, name, a.args, duration=0.0, line=a.line))
        elif key in ends and open_runs.get((ends[key], a.args)):
            k = open_runs[(ends[key], a.args)].pop(0)
            out[k] = replace(out[k], duration=round(a.time - out[k].time, 6))
        else:
            out.append(a)
    return Plan(tuple(out), plan.events, plan.end)
