"""Reading and writing plans: VAL's format, ENHSP's output, the paper's style (Fig. 6).

VAL format, one action a line::

    0.0: (start-increase L1 L2 z-axis)
    3.5: (stop-increase L1 L2 z-axis)  [1.0]   ; a duration and a comment are accepted
    ; 6.708204: (back-to-zero L2 z-axis)        <- an event the simulator predicts

Comment lines of the form ``; t: (name args)`` (or ``;t: ...`` as in the paper) are read back
as events; other comments are ignored. ENHSP additions, accepted everywhere:
``t: -----waiting---- [t2]`` (the plan lasts at least until t2) and ``T: @PlanEND`` (the plan
ends at T): both set :attr:`Plan.end`. Lines naming an event (``event_names``) become events,
as ENHSP prints them with ``-pe``.

Times are written with up to 6 decimals (trailing zeros dropped, at least one decimal).
"""

from __future__ import annotations

import functools
import os
from collections.abc import Collection, Iterable

from artiplan.errors import InputError, SourceLocation
from artiplan.semantics.plan import Plan, TimedAction, TimedEvent

_NUM = r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?"


class _Patterns:
    """The reader's regular expressions, compiled when a plan is first read (not at import:
    ``artiplan plan`` only writes plans)."""

    def __init__(self) -> None:
        import re  # here: importing it is a share of a short command's start

        self.time = re.compile(rf"\s*({_NUM})\s*:\s*")
        self.number = re.compile(rf"\s*{_NUM}\s*")
        self.action = re.compile(r"\(\s*([^()\s;]+)((?:\s+[^()\s;]+)*)\s*\)\s*")
        self.duration = re.compile(rf"\[\s*({_NUM})\s*\]\s*")
        self.waiting = re.compile(rf"-+\s*waiting\s*-+\s*(?:\[\s*({_NUM})\s*\])?\s*",
                                  re.IGNORECASE)
        self.planend = re.compile(r"@PlanEND\s*", re.IGNORECASE)
        self.event_comment = re.compile(
            rf";+\s*({_NUM})\s*:\s*\(\s*([^()\s]+)((?:\s+[^()\s]+)*)\s*\)\s*$")


@functools.cache
def _patterns() -> _Patterns:
    return _Patterns()


def format_time(t: float) -> str:
    """``t`` [s] with up to 6 decimals: 1.0, 0.5, 6.708204."""
    s = f"{round(t, 6) + 0.0:.6f}".rstrip("0")
    return s + "0" if s.endswith(".") else s


def parse_plan(text: str, filename: str = "<plan>", event_names: Collection[str] = ()) -> Plan:
    """Parse a plan in VAL's format (or ENHSP's, see the module docstring).

    Raises InputError (file:line:col, expected, found) on a malformed line or a negative time.
    Unknown action names are *not* an error here: the validator reports them ("bad operator").
    """
    events_lower = {e.lower() for e in event_names}
    event_comment = _patterns().event_comment
    actions: list[TimedAction] = []
    events: list[TimedEvent] = []
    end: float | None = None
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.rstrip()
        stripped = line.lstrip()
        if not stripped:
            continue
        if stripped.startswith(";"):
            m = event_comment.match(stripped)
            if m:
                events.append(TimedEvent(float(m.group(1)), m.group(2), tuple(m.group(3).split())))
            continue
        item = _parse_line(line, lineno, filename)
        if isinstance(item, float):
            end = item if end is None else max(end, item)
        elif item.name.lower() in events_lower:
            events.append(TimedEvent(item.time, item.name, item.args))
        else:
            actions.append(item)
    return Plan(tuple(actions), tuple(events), end)


def _parse_line(line: str, lineno: int, filename: str) -> TimedAction | float:
    """One non-comment line: a TimedAction, or the end time a waiting/@PlanEND line gives."""

    def error(col: int, expected: str) -> InputError:
        found = line[col:].split(";")[0].strip() or "end of line"
        return InputError(
            "malformed plan line",
            SourceLocation(filename, lineno, col + 1),
            expected=expected,
            found=found[:40],
        )

    pat = _patterns()
    m = pat.time.match(line)
    if not m:
        if mn := pat.number.match(line):
            raise error(mn.end(), "':' after the time")
        raise error(len(line) - len(line.lstrip()), "a time 't:' (VAL format 't: (action args)')")
    t = float(m.group(1))
    if t < 0:
        raise error(m.start(1), "a non-negative time")
    pos = m.end()
    result: TimedAction | float
    if mw := pat.waiting.match(line, pos):
        result, pos = (float(mw.group(1)) if mw.group(1) else t), mw.end()
    elif mp := pat.planend.match(line, pos):
        result, pos = t, mp.end()
    elif ma := pat.action.match(line, pos):
        pos = ma.end()
        duration = None
        if md := pat.duration.match(line, pos):
            duration, pos = float(md.group(1)), md.end()
        result = TimedAction(t, ma.group(1), tuple(ma.group(2).split()), duration, line=lineno)
    else:
        raise error(pos, "'(name args)'")
    if pos < len(line) and not line[pos:].lstrip().startswith(";"):
        raise error(pos, "end of line or a ';' comment")
    return result


def read_plan(path: str | os.PathLike[str], event_names: Collection[str] = ()) -> Plan:
    """Read a plan file (VAL or ENHSP ``-sp`` format)."""
    name = os.fspath(path)
    try:
        with open(name) as fh:
            text = fh.read()
    except OSError as exc:
        raise InputError(f"cannot read plan {name!r}: {exc.strerror}") from None
    return parse_plan(text, name, event_names)


def read_plan_for(path: str | os.PathLike[str], event_names: Collection[str]) -> Plan:
    """Read a plan file the way ``artiplan validate`` does: as VAL does (a line naming an event
    stays an action, so the validator reports it as a bad operator), except in ENHSP's files
    (recognised by ``@PlanEND`` or ``-----waiting----``), whose event lines become events."""
    plan = read_plan(path)
    return read_plan(path, event_names) if plan.end is not None else plan


def parse_enhsp_output(text: str, event_names: Collection[str] = ()) -> Plan:
    """The plan in ENHSP's printed output (``Found Plan:`` lines), ignoring everything else."""
    keep: list[str] = []
    started, time = False, _patterns().time
    for line in text.splitlines():
        if line.strip().startswith("Found Plan"):
            started, keep = True, []
            continue
        if started and time.match(line) and ("(" in line or "waiting" in line or "@" in line):
            keep.append(line)
        elif started and keep and not line.strip():
            started = False
    return parse_plan("\n".join(keep), "<enhsp output>", event_names)


def format_plan(plan: Plan, events: bool = True, end_comment: bool = False) -> str:
    """VAL text of ``plan``; with ``events`` the paper's style: events as ``; t: (event)`` lines,
    before the actions of their instant unless those actions triggered them."""
    items: list[tuple[float, int, int, str]] = []
    for k, a in enumerate(plan.actions):
        dur = f" [{format_time(a.duration)}]" if a.duration is not None else ""
        items.append((round(a.time, 6), 1, k, f"{format_time(a.time)}: {a.signature}{dur}"))
    if events:
        for k, e in enumerate(plan.events):
            phase = 2 if e.after_actions else 0
            items.append((round(e.time, 6), phase, k, f"; {format_time(e.time)}: {e.signature}"))
    lines = [s for *_, s in sorted(items)]
    if end_comment and plan.end is not None:
        lines.append(f"; end: {format_time(plan.end)}")
    return "\n".join(lines) + ("\n" if lines else "")


def write_plan(plan: Plan, path: str | os.PathLike[str], events: bool = True) -> None:
    """Write ``plan`` in VAL's format (with event comment lines when ``events``)."""
    with open(path, "w") as fh:
        fh.write(format_plan(plan, events))


def with_events(plan: Plan, events: Iterable[TimedEvent]) -> Plan:
    """``plan`` with its predicted events replaced by ``events``."""
    return Plan(plan.actions, tuple(events), plan.end)
