"""Turn other planners' plan text into artiplan's :class:`~artiplan.semantics.plan.Plan`.

The readers themselves live in :mod:`artiplan.semantics.plan_io`; this module only picks the
right one for each backend's output.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from artiplan.semantics.plan import Plan


def plan_from_enhsp(text: str) -> Plan:
    """A plan from ENHSP's output (``t: (action)``, ``-----waiting----``, ``@PlanEND`` lines)."""
    try:
        from artiplan.semantics.plan_io import read_enhsp_output
    except ImportError:  # until the semantics stage lands
        return _interim_read(text)
    return read_enhsp_output(text)


def plan_from_val(text: str) -> Plan:
    """A plan in VAL's format (``t: (name args) [d]`` lines, ``;`` comments)."""
    try:
        from artiplan.semantics.plan_io import read_val_plan
    except ImportError:  # until the semantics stage lands
        return _interim_read(text)
    return read_val_plan(text)


_LINE = re.compile(r"^\s*([0-9.eE+-]+)\s*:\s*(\(.*?\)|@PlanEND|-----waiting----)")


def _interim_read(text: str) -> Plan:
    """A minimal reader used only until :mod:`artiplan.semantics.plan_io` exists.

    Same-instant actions are spread by 1 ms (VAL applies same-time actions in parallel), and a
    final ``@PlanEND`` after the last action becomes an ``observe`` action at that time.
    """
    from artiplan.semantics.plan import Plan, TimedAction

    actions: list[TimedAction] = []
    for line in text.splitlines():
        match = _LINE.match(line.split(";", 1)[0])
        if match is None or match.group(2).startswith("-"):
            continue
        time = float(match.group(1))
        if actions and time <= actions[-1].time:
            time = actions[-1].time + 0.001
        if match.group(2) == "@PlanEND":
            if not actions or time > actions[-1].time + 1e-9:
                actions.append(TimedAction(time, "observe"))
            continue
        name, *args = match.group(2)[1:-1].split()
        actions.append(TimedAction(time, name, tuple(args)))
    return Plan(tuple(actions))
