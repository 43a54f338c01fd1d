"""Which pairs of actions interfere (VAL's mutex), and small helpers of states and printing."""

from __future__ import annotations

from artiplan.pddl.task import (
    TRUE,
    And,
    Atom,
    Comparison,
    ConditionalEffect,
    Const,
    Effect,
    FluentRef,
    GroundAction,
    Not,
    NumericEffect,
)
from artiplan.semantics import State, format_condition, interferes


def act(name: str, pre=TRUE, **effect) -> GroundAction:  # type: ignore[no-untyped-def]
    return GroundAction(name, (), pre, Effect(**effect))


def inc(i: int, op: str = "increase") -> NumericEffect:
    return NumericEffect(op, i, Const(1.0))  # type: ignore[arg-type]


def test_reading_what_the_other_writes_interferes() -> None:
    stop = act("stop", Atom(0), delete=(0,))
    start = act("start", Not(Atom(0)), add=(0,))
    assert interferes(stop, start) and interferes(start, stop)
    reader = act("r", Comparison(">", FluentRef(1), Const(0.0)))
    assert interferes(reader, act("w", numeric=(inc(1),)))


def test_independent_and_commutative_actions_do_not_interfere() -> None:
    assert not interferes(act("a", Atom(0), add=(1,)), act("b", Atom(0), add=(1,)))
    assert not interferes(act("a", numeric=(inc(0),)), act("b", numeric=(inc(0, "decrease"),)))
    assert not interferes(act("observe"), act("observe"))


def test_assignments_and_add_delete_conflicts_interfere() -> None:
    assert interferes(act("a", numeric=(inc(0, "assign"),)), act("b", numeric=(inc(0),)))
    assert interferes(act("a", add=(3,)), act("b", delete=(3,)))
    # A conditional effect's condition is read; its effect is written.
    cond = GroundAction(
        "c", (), TRUE, Effect(conditional=(ConditionalEffect(Atom(5), Effect(add=(6,))),))
    )
    assert interferes(cond, act("d", delete=(5,)))
    assert interferes(cond, act("e", delete=(6,)))


def test_state_facts_are_a_bit_mask() -> None:
    state = State(1.0, 0b101, (1.0, 2.0))
    assert state.holds_fact(0) and not state.holds_fact(1) and state.holds_fact(2)


def test_format_condition_without_a_task() -> None:
    cond = And((Atom(2), Not(Comparison(">=", FluentRef(0), Const(360.0)))))
    assert format_condition(cond) == "(and (fact#2) (not (>= (fluent#0) 360)))"
