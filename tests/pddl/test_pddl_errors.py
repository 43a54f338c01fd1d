"""Every kind of input error, with the file, line and column it points at."""

from __future__ import annotations

import pytest

from artiplan.errors import ExitCode, InputError
from artiplan.pddl import ground, load_task, parse_domain, parse_problem

DOMAIN = """(define (domain d)
  (:requirements :typing :numeric-fluents)
  (:types block - object table)
  (:constants T1 - table)
  (:predicates (on ?b - block ?t - table) (clear ?b - block))
  (:functions (weight ?b - block) (total))
  (:action lift
    :parameters (?b - block ?t - table)
    :precondition (and (on ?b ?t) (clear ?b) (< (weight ?b) 5))
    :effect (and (not (on ?b ?t)) (increase (total) (weight ?b)))))
"""

PROBLEM = """(define (problem p) (:domain d)
  (:objects b1 b2 - block)
  (:init (on b1 T1) (clear b1) (= (weight b1) 2) (= (total) 0))
  (:goal (not (on b1 T1))))
"""


def domain_error(text: str) -> InputError:
    with pytest.raises(InputError) as info:
        parse_domain(text, "dom.pddl")
    return info.value


def problem_error(text: str) -> InputError:
    with pytest.raises(InputError) as info:
        ground(parse_domain(DOMAIN, "dom.pddl"), parse_problem(text, "prob.pddl"))
    return info.value


def where(err: InputError) -> tuple[str, int, int]:
    assert err.location is not None
    return err.location.file, err.location.line, err.location.column


def test_the_fixture_itself_is_fine() -> None:
    task = load_task(DOMAIN, PROBLEM)
    assert [a.signature for a in task.actions] == ["(lift b1 T1)"]
    assert task.warnings == ()


@pytest.mark.parametrize(
    ("old", "new", "line", "col", "found"),
    [
        # unbalanced: the '(' of `(define` is never closed
        ("(weight ?b)))))\n", "(weight ?b))))\n", 1, 1, "end of file"),
        # an extra ')' after the end
        ("(weight ?b)))))\n", "(weight ?b))))))\n", 10, 68, ")"),
        ("(:functions", "(:fonctions", 6, 4, ":fonctions"),
        ("(:types block - object table)", "(:types block - )", 3, 17, "-"),
        ("(clear ?b) (<", "(not (clear ?b) (on ?b ?t)) (<", 9, 51, "(on ...)"),
        (":precondition (and", ":precond (and", 9, 5, ":precond"),
        ("(clear ?b) (<", "(clear ?b) (imply (clear ?b)) (<", 9, 46, "(imply ...)"),
        ("(not (on ?b ?t))", "(or (on ?b ?t))", 10, 18, "(or ...)"),
        ("?b - block ?t - table)\n    :pre", "?b - block 7 - table)\n    :pre", 8, 29, "7"),
    ],
)
def test_syntax_errors(old: str, new: str, line: int, col: int, found: str) -> None:
    assert old in DOMAIN
    err = domain_error(DOMAIN.replace(old, new, 1))
    assert where(err) == ("dom.pddl", line, col)
    assert err.found == found
    assert err.expected
    assert str(err).startswith(f"dom.pddl:{line}:{col}: ")
    assert err.exit_code == ExitCode.BAD_INPUT


@pytest.mark.parametrize(
    ("old", "new", "line", "col", "message"),
    [
        ("(clear ?b) (<", "(free ?b) (<", 9, 35, "undeclared predicate 'free'"),
        ("(< (weight ?b) 5)", "(< (mass ?b) 5)", 9, 49, "undeclared function 'mass'"),
        ("(on ?b ?t) (clear", "(on ?b T2) (clear", 9, 31, "undeclared object or constant 'T2'"),
        ("(clear ?b) (<", "(clear ?c) (<", 9, 42, "unbound variable '?c'"),
        ("(?b - block ?t - table)", "(?b - blok ?t - table)", 8, 18, "undeclared type 'blok'"),
        ("(clear ?b) (<", "(clear ?b ?t) (<", 9, 35, "predicate 'clear' takes 1 argument(s)"),
        ("(increase (total) (weight ?b))", "(increase (total ?b) (weight ?b))", 10, 45,
         "function 'total' takes 0 argument(s)"),
        ("(clear ?b) (<", "(clear ?t) (<", 9, 42, "type error"),
        ("(on ?b ?t) (clear", "(on T1 ?t) (clear", 9, 28, "type error"),
        ("(weight ?b)))))", "(* #t (weight ?b))))))", 10, 35, "#t in the effect of action"),
    ],
)
def test_declaration_and_type_errors(old: str, new: str, line: int, col: int,
                                     message: str) -> None:
    assert old in DOMAIN
    err = domain_error(DOMAIN.replace(old, new, 1))
    assert where(err) == ("dom.pddl", line, col)
    assert message in str(err)


@pytest.mark.parametrize(
    ("old", "new", "line", "col", "message"),
    [
        ("(clear b1)", "(clear b3)", 3, 28, "undeclared object or constant 'b3'"),
        ("(clear b1)", "(clear T1)", 3, 28, "type error"),
        ("(= (weight b1) 2)", "(= (weight b1 b2) 2)", 3, 35, "takes 1 argument(s), found 2"),
        ("(:goal (not (on b1 T1)))", "(:goal (not (on b1 b2)))", 4, 22, "type error"),
        ("b1 b2 - block", "b1 b2 - brick", 2, 13, "undeclared type 'brick'"),
        ("(= (total) 0)", "(= (total) zero)", 3, 61, "initial values must be numbers"),
    ],
)
def test_problem_errors(old: str, new: str, line: int, col: int, message: str) -> None:
    assert old in PROBLEM
    err = problem_error(PROBLEM.replace(old, new, 1))
    assert where(err) == ("prob.pddl", line, col)
    assert message in str(err)


def test_discrete_numeric_effect_in_a_process_is_an_error() -> None:
    text = DOMAIN.replace("(:action lift", "(:process lift").replace(
        "(increase (total) (weight ?b))", "(assign (total) 1)")
    err = domain_error(text)
    assert where(err) == ("dom.pddl", 10, 35)
    assert "discrete numeric effect" in str(err)


def test_durative_actions_ground_into_pddl_plus() -> None:
    text = DOMAIN.replace(")))\n", "))\n  (:durative-action wait :parameters () :duration "
                          "(= ?duration 2) :condition (at start (clear b1)) :effect "
                          "(at end (clear b1))))\n")
    text = text.replace("(:constants T1 - table)", "(:constants T1 - table b1 - block)")
    domain = parse_domain(text, "dom.pddl")
    assert domain.operators[-1].kind == "durative-action"
    task = ground(domain, parse_problem(PROBLEM.replace("b1 b2 - block", "b2 - block"), "p"))
    assert task.durative == ("wait",)
    assert {a.name for a in task.actions} >= {"wait@start", "wait@end"}
    assert [p.name for p in task.processes] == ["wait@during"]


def test_harmless_quirks_are_warnings_with_their_place() -> None:
    """An undeclared predicate in :init (ENHSP ignores it) and '? b' (a space after '?')."""
    problem = parse_problem(PROBLEM.replace("(clear b1)", "(clear b1) (clean b1)"), "prob.pddl")
    task = ground(parse_domain(DOMAIN.replace("?b - block ?t", "? b - block ?t"), "dom.pddl"),
                  problem)
    assert any("prob.pddl:3:" in w and "'clean'" in w and "ignored" in w for w in task.warnings)
    assert any(w.startswith("dom.pddl:5:20:") and "'? b' read as '?b'" in w for w in task.warnings)
    assert not any("clean" in f for f in task.facts)


def test_empty_and_truncated_files() -> None:
    assert where(domain_error("  ; nothing\n")) == ("dom.pddl", 1, 1)
    err = domain_error("(define (domain d)\n  (:predicates (p)")
    assert where(err) == ("dom.pddl", 2, 3)
    err = domain_error("(define (problem d))")
    assert where(err) == ("dom.pddl", 1, 10) and err.expected == "(domain NAME)"
