"""parse -> write -> parse gives the same tree: hand-written quirky files and the suite."""

from __future__ import annotations

from pathlib import Path

from artiplan.pddl import parse_domain, parse_problem, write_domain, write_problem
from artiplan.pddl import syntax as s

QUIRKY_DOMAIN = """
;; Quirky formatting: upper-case keywords, comments inside lists, no space in `?x -type`.
(DEFINE (DOMAIN Quirky) ; trailing comment
  (:REQUIREMENTS :typing :fluents :adl :time)
  (:types truck car - vehicle
          depot - place vehicle place)   ; `place`: a parent before it is declared
  (:constants Home - depot)
  (:predicates (at ?v -vehicle ?p -place) (loaded ?v - (either truck car))
               (visited ?p - place) (ok))
  (:functions (fuel ?v - vehicle) (dist ?a ?b - place) - number
              (total-cost) - number (level))
  (:action Drive
    :parameters (?v -vehicle ?from ?to -place)
    :precondition (AND (at ?v ?from) (not (= ?from ?to))
                       (>= (fuel ?v) (* 0.5 (dist ?from ?to)))
                       (imply (loaded ?v) (exists (?d - depot) (visited ?d))))
    :effect (and (not (at ?v ?from)) (at ?v ?to)
                 (decrease (fuel ?v) (/ (dist ?from ?to) 2))
                 (increase (total-cost) (+ 1 (dist ?from ?to) .5 -3))
                 (scale-up (level) 1e-3) (scale-down (level) 2)
                 (when (visited ?to) (assign (level) (- (level))))
                 (forall (?p - place) (when (= ?p ?to) (visited ?p)))))
  (:process burn
    :parameters (?v - truck)
    :precondition (or (ok) (forall (?p - place) (visited ?p)))
    :effect (and (decrease (fuel ?v) (* #t 0.1)) (increase (level) (* (fuel ?v) #t))))
  (:event empty :parameters (?v - vehicle)
    :precondition (<= (fuel ?v) 0) :effect (not (ok)))
  (:durative-action wait
    :parameters ()
    :duration (= ?duration 5)
    :condition (and (at start (ok)) (over all (ok)))
    :effect (and (at end (not (ok))) (increase (level) (* #t 2)))))
"""

QUIRKY_PROBLEM = """(define (problem Q1) (:domain QUIRKY)
  (:objects t1 - truck c1 - car Depot2 - depot x y - place z)
  (:init (AT t1 home) (at C1 x) (= (fuel t1) 10) (= (fuel c1) -.5)
         (= (dist home x) 3.25) (= (total-cost) 0) (= (level) 1)) ; comment
  (:goal (and (at t1 x) (forall (?p - place) (imply (visited ?p) (ok)))))
  (:metric minimize (+ (total-cost) (* 2 (level)))))
"""


def test_quirky_domain_round_trip() -> None:
    tree = parse_domain(QUIRKY_DOMAIN, "quirky.pddl")
    again = parse_domain(write_domain(tree), "written.pddl")
    assert again == tree
    # Spot checks that the tree says what the text says.
    assert [t.name for t in tree.types if t.types == ("vehicle",)] == ["truck", "car"]
    assert tree.predicates[1].parameters[0].types == ("truck", "car")
    assert [f.return_type for f in tree.functions] == ["number", "number", "number", None]
    drive = tree.operators[0]
    assert [p.types for p in drive.parameters] == [("vehicle",), ("place",), ("place",)]
    assert [o.kind for o in tree.operators] == ["action", "process", "event", "durative-action"]
    assert isinstance(drive.effect, s.EffectConjunction)
    cost = drive.effect.parts[3]
    assert isinstance(cost, s.NumericAssignment) and isinstance(cost.expr, s.Arithmetic)
    assert [a.value for a in cost.expr.args if isinstance(a, s.Number)] == [1.0, 0.5, -3.0]


def test_quirky_problem_round_trip() -> None:
    tree = parse_problem(QUIRKY_PROBLEM, "q.pddl")
    assert parse_problem(write_problem(tree), "w.pddl") == tree
    assert tree.objects[-1] == s.TypedName("z")  # untyped, after typed ones
    values = [i.value for i in tree.init if isinstance(i, s.InitValue)]
    assert values == [10.0, -0.5, 3.25, 0.0, 1.0]
    assert tree.metric is not None and tree.metric.direction == "minimize"


def test_untyped_group_before_typed_one_keeps_its_type() -> None:
    tree = s.Problem("p", "d", objects=(s.TypedName("a"), s.TypedName("b", ("t",))))
    text = write_problem(tree)
    assert "a - object b - t" in text


def test_equality_is_not_a_numeric_comparison() -> None:
    dom = parse_domain(QUIRKY_DOMAIN)
    pre = dom.operators[0].precondition
    assert isinstance(pre, s.Conjunction)
    neg = pre.parts[1]
    assert isinstance(neg, s.Negation) and isinstance(neg.operand, s.Equals)
    dur = dom.operators[3].duration
    assert isinstance(dur, s.Compare) and dur.left == s.Special("?duration")


def test_predicate_named_at_is_an_atom_not_a_time_specifier() -> None:
    dom = parse_domain(QUIRKY_DOMAIN)
    pre = dom.operators[0].precondition
    assert isinstance(pre, s.Conjunction)
    assert pre.parts[0] == s.AtomicFormula("at", (s.Variable("?v"), s.Variable("?from")))


def test_suite_files_round_trip(suite_dir: Path) -> None:
    domains = sorted(suite_dir.glob("*/domain.pddl"))
    problems = sorted(suite_dir.glob("*/p*.pddl"))
    assert len(domains) >= 3 and len(problems) >= 100
    for path in domains:
        tree = parse_domain(path.read_text(), str(path))
        assert parse_domain(write_domain(tree)) == tree, path
    for path in problems:
        tree = parse_problem(path.read_text(), str(path))
        assert parse_problem(write_problem(tree)) == tree, path
