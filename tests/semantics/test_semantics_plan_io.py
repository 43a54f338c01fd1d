"""Plan files: VAL format, the paper's style, ENHSP's output; errors with locations."""

from __future__ import annotations

import pytest

from artiplan.errors import InputError
from artiplan.semantics import Plan, TimedAction, TimedEvent
from artiplan.semantics.plan_io import format_plan, format_time, parse_enhsp_output, parse_plan

PAPER = """\
;1.0: (back-to-360 L4 z-axis)
1.00: (start-decrease L1 L2 z-axis)
;8.0: (back-to-360 L3 z-axis)
9.00: (stop-decrease L1 L2 z-axis)
10.0: (start-increase L1 L2 xy-axes)  ; a comment
12.0: (stop-increase L1 L2 xy-axes) [0.5]
"""


def test_reads_the_papers_figure_6_style() -> None:
    plan = parse_plan(PAPER)
    assert [(a.time, a.name) for a in plan.actions] == [
        (1.0, "start-decrease"), (9.0, "stop-decrease"), (10.0, "start-increase"),
        (12.0, "stop-increase"),
    ]
    assert plan.actions[0].args == ("L1", "L2", "z-axis")
    assert plan.actions[3].duration == 0.5 and plan.actions[3].line == 6
    assert plan.events == (
        TimedEvent(1.0, "back-to-360", ("L4", "z-axis")),
        TimedEvent(8.0, "back-to-360", ("L3", "z-axis")),
    )


def test_writes_and_reads_back() -> None:
    plan = Plan(
        (TimedAction(0.0, "start-increase", ("L1", "L2", "z-axis")),
         TimedAction(3.5123456789, "stop-increase", ("L1", "L2", "z-axis"))),
        (TimedEvent(0.5, "back-to-zero", ("L2", "z-axis")),
         TimedEvent(3.5123456789, "reset", ("L2",), after_actions=True)),
    )
    text = format_plan(plan)
    assert text.splitlines() == [
        "0.0: (start-increase L1 L2 z-axis)",
        "; 0.5: (back-to-zero L2 z-axis)",
        "3.512346: (stop-increase L1 L2 z-axis)",
        "; 3.512346: (reset L2)",
    ]
    again = parse_plan(text)
    assert [a.signature for a in again.actions] == [a.signature for a in plan.actions]
    assert again.actions[1].time == 3.512346
    assert [e.signature for e in again.events] == [e.signature for e in plan.events]


def test_format_time() -> None:
    assert [format_time(t) for t in (0, 1, 0.5, 6.7082039325, 12.0000004)] == [
        "0.0", "1.0", "0.5", "6.708204", "12.0"
    ]


@pytest.mark.parametrize(
    ("text", "line", "col"),
    [
        ("0.0: (a)\n1.0 (b)\n", 2, 5),  # missing colon
        ("0.0: a b\n", 1, 6),  # no parentheses
        ("\n\n  -1: (a)\n", 3, 3),  # negative time
        ("0.0: (a) junk\n", 1, 10),  # trailing text
        ("(a)\n", 1, 1),  # no time
        ("0.0: (a\n", 1, 6),  # unclosed
    ],
)
def test_malformed_lines_are_input_errors_with_locations(text: str, line: int, col: int) -> None:
    with pytest.raises(InputError) as info:
        parse_plan(text, "plan.txt")
    assert info.value.location is not None
    assert (info.value.location.file, info.value.location.line) == ("plan.txt", line)
    assert info.value.location.column == col
    assert str(info.value).startswith(f"plan.txt:{line}:{col}:")


def test_enhsp_sp_file_and_printed_output() -> None:
    sp = "0: (start-increase L1 L2 xy-axes)\n9.0: (back-to-zero L2 xy-axes)\n12.0: @PlanEND \n"
    plan = parse_plan(sp, event_names={"back-to-zero"})
    assert [a.name for a in plan.actions] == ["start-increase"]
    assert [e.name for e in plan.events] == ["back-to-zero"]
    assert plan.end == 12.0 and plan.makespan == 12.0
    out = """Extracting plan with execution delta: 1.0
Problem Solved

Found Plan:
0: (start-increase L1 L2 xy-axes)
0: -----waiting---- [9.0]
9.0: (back-to-zero L2 xy-axes)
9.0: -----waiting---- [12.0]

Plan-Length:14
Elapsed Time: 12.0
"""
    printed = parse_enhsp_output(out, event_names={"back-to-zero"})
    assert printed == plan
