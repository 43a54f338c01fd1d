"""Grounding: counts computed by hand, static folding, pruning, the process quirk."""

from __future__ import annotations

from math import comb
from pathlib import Path

import pytest

from artiplan.errors import InputError
from artiplan.pddl import load_task, parse_domain, parse_problem
from artiplan.pddl.task import (
    TRUE,
    And,
    Atom,
    Comparison,
    ConditionalEffect,
    Const,
    ContinuousEffect,
    Effect,
    FluentRef,
    Not,
    Or,
)


def test_counts_by_hand(arm_domain: str, arm_problem: str) -> None:
    task = load_task(arm_domain, arm_problem)
    # start/stop-increase: 2 connected pairs x 2 planes each; events: 3 links x 2 planes;
    # move-increase: only L2, L3 can ever be moved (4), L1 pruned (2); propagate: 1 pair x 2;
    # gravity: 3 links.
    assert (task.stats.actions, task.stats.events, task.stats.processes) == (8, 6, 9)
    # Naive instances: start/stop 3*3*2 each, move 3*2, propagate 3*3*2, gravity 3, events 3*2.
    assert task.stats.pruned == (18 + 18 + 6 + 18 + 3 + 6) - (8 + 6 + 9)
    # in-use, free-to-move x3, increasing-angle-robot L2/L3 x 2 planes, -gravity x3.
    assert task.stats.facts == 11
    assert len(task.fluents) == 6  # angles only: speeds are static and folded
    assert "(angle L2 z-axis)" in task.fluents
    assert "(increasing-angle-robot L1 z-axis)" not in task.facts


def test_static_folding(arm_domain: str, arm_problem: str) -> None:
    task = load_task(arm_domain, arm_problem)
    start = task.action_by_signature("(start-increase L1 L2 z-axis)")
    # (connected L1 L2) is static and true: only (not (in-use)) is left.
    assert start.precondition == Not(Atom(task.fact_index("(in-use)")))
    move = next(p for p in task.processes if p.signature == "(move-increase L2 xy-axes)")
    fl = task.fluent_index("angle(L2,xy-axes)")
    assert move.continuous == (ContinuousEffect(fl, Const(10.0)),)
    assert task.init_values[task.fluent_index("(angle L2 z-axis)")] == -3.0
    assert task.init_values[task.fluent_index("(angle L3 xy-axes)")] == 0.001
    assert task.goal == And((
        Comparison(">", FluentRef(task.fluent_index("(angle L2 xy-axes)")), Const(265.4)),
        Comparison("<", FluentRef(task.fluent_index("(angle L3 z-axis)")), Const(5.5)),
    ))


def test_process_setting_a_fact_warns_and_goes_to_discrete(arm_domain: str,
                                                           arm_problem: str) -> None:
    domain = parse_domain(arm_domain, "arm.pddl")
    assert any("gravity-increase" in w and "arm.pddl:31:" in w for w in domain.warnings)
    task = load_task(arm_domain, arm_problem)
    grav = next(p for p in task.processes if p.signature == "(gravity-increase L2)")
    assert grav.discrete.add == (task.fact_index("(increasing-angle-gravity L2)"),)


def test_undeclared_function_in_init_warns(arm_domain: str, arm_problem: str) -> None:
    task = load_task(arm_domain, arm_problem)
    assert any("'foo'" in w and "never declared" in w for w in task.warnings)
    problem = parse_problem(arm_problem, "p.pddl")
    assert problem.objects[0].name == "L1"


ROOMS = """(define (domain rooms)
  (:requirements :typing :adl)
  (:types room ball)
  (:predicates (at-robby ?r - room) (at ?b - ball ?r - room) (carry ?b - ball)
               (adjacent ?a ?b - room) (lit ?r - room) (painted ?r - room))
  (:action move :parameters (?from ?to - room)
    :precondition (and (at-robby ?from) (adjacent ?from ?to) (not (= ?from ?to)))
    :effect (and (not (at-robby ?from)) (at-robby ?to) (when (not (lit ?to)) (lit ?to))))
  (:action pick :parameters (?b - ball ?r - room)
    :precondition (and (at ?b ?r) (at-robby ?r) (forall (?c - ball) (not (carry ?c))))
    :effect (and (carry ?b) (not (at ?b ?r))))
  (:action drop-all :parameters (?r - room)
    :precondition (exists (?b - ball) (carry ?b))
    :effect (forall (?b - ball) (when (carry ?b) (and (at ?b ?r) (not (carry ?b))))))
  (:action switch :parameters (?r - room)
    :precondition (imply (lit ?r) (at-robby ?r))
    :effect (not (lit ?r)))
  (:action paint :parameters (?r - room) :precondition (at-robby ?r) :effect (painted ?r)))
"""

ROOMS_PROBLEM = """(define (problem rooms1) (:domain rooms)
  (:objects r1 r2 r3 r4 - room b1 b2 - ball)
  (:init (at-robby r1) (at b1 r1) (at b2 r3) (lit r1) (painted r1)
         (adjacent r1 r2) (adjacent r2 r1) (adjacent r2 r3) (adjacent r3 r2) (adjacent r1 r1))
  (:goal (and (painted r1) (painted r3) (at b2 r1))))
"""


def test_adl_counts_by_hand() -> None:
    task = load_task(ROOMS, ROOMS_PROBLEM)
    names = [a.signature for a in task.actions]
    # move: 4 adjacent pairs ((r1 r1) fails the inequality); pick: 2 balls x r1..r3 (robby
    # never reaches r4: 2 pruned); drop-all: 4 rooms; switch: 4; paint: r1..r3 (r4 pruned).
    assert len(names) == 4 + 6 + 4 + 4 + 3
    # Naive instances: move 4*4, pick 2*4, drop-all 4, switch 4, paint 4.
    assert task.stats.pruned == (16 + 8 + 4 + 4 + 4) - len(names)
    assert "(move r1 r1)" not in names and "(pick b1 r4)" not in names
    # at-robby r1..r3, at: 2 balls x 4 rooms (drop-all reaches r4), carry x2, lit r1..r3,
    # painted r2, r3 ((painted r1) is true and never deleted: folded away).
    assert task.stats.facts == 3 + 8 + 2 + 3 + 2
    assert "(painted r1)" not in task.facts and "(lit r4)" not in task.facts


def test_quantifiers_imply_when_equality() -> None:
    task = load_task(ROOMS, ROOMS_PROBLEM)
    f = task.fact_index
    pick = task.action_by_signature("(pick b2 r3)")
    assert pick.precondition == And((Atom(f("(at b2 r3)")), Atom(f("(at-robby r3)")),
                                     Not(Atom(f("(carry b1)"))), Not(Atom(f("(carry b2)")))))
    drop = task.action_by_signature("(drop-all r2)")
    assert drop.precondition == Or((Atom(f("(carry b1)")), Atom(f("(carry b2)"))))
    assert drop.effect.conditional == (
        ConditionalEffect(Atom(f("(carry b1)")), Effect(add=(f("(at b1 r2)"),),
                                                        delete=(f("(carry b1)"),))),
        ConditionalEffect(Atom(f("(carry b2)")), Effect(add=(f("(at b2 r2)"),),
                                                        delete=(f("(carry b2)"),))),
    )
    move = task.action_by_signature("(move r1 r2)")
    assert move.effect.conditional == (
        ConditionalEffect(Not(Atom(f("(lit r2)"))), Effect(add=(f("(lit r2)"),))),)
    switch = task.action_by_signature("(switch r1)")
    assert switch.precondition == Or((Not(Atom(f("(lit r1)"))), Atom(f("(at-robby r1)"))))
    # (lit r4) can never hold: the implication is vacuously true, the delete is dropped.
    switch4 = task.action_by_signature("(switch r4)")
    assert switch4.precondition == TRUE and switch4.effect == Effect()
    assert task.goal == And((Atom(f("(painted r3)")), Atom(f("(at b2 r1)"))))
    assert {task.facts[i] for i in task.init_facts} == {"(at-robby r1)", "(at b1 r1)",
                                                        "(at b2 r3)", "(lit r1)"}


def test_paths_and_text_both_load(tmp_path: Path, arm_domain: str, arm_problem: str) -> None:
    d = tmp_path / "d.pddl"
    d.write_text(arm_domain)
    p = tmp_path / "p.pddl"
    p.write_text(arm_problem)
    a, b = load_task(d, str(p)), load_task(arm_domain, arm_problem)
    assert (a.facts, a.fluents, a.actions, a.processes) == (b.facts, b.fluents, b.actions,
                                                            b.processes)


def test_undefined_static_fluent_comparison_is_false() -> None:
    domain = ROOMS.replace("(:predicates", "(:functions (cost ?r - room))\n  (:predicates").replace(
        ":precondition (at-robby ?r) :effect", ":precondition (and (at-robby ?r) "
        "(< (cost ?r) 5)) :effect")
    problem = ROOMS_PROBLEM.replace("(painted r1)", "(painted r1) (= (cost r2) 1)")
    task = load_task(domain, problem)
    assert [a.signature for a in task.actions if a.name == "paint"] == ["(paint r2)"]
    assert task.fluents == ()  # (cost r2) is static: folded into the condition, which is true


@pytest.mark.parametrize("n", [3, 8, 12])
def test_suite_ng_counts_follow_the_encoding(suite_dir: Path, n: int) -> None:
    task = load_task(suite_dir / "ng" / "domain.pddl", suite_dir / "ng" / f"p{n}-1.pddl")
    # start/stop x increase/decrease for n-1 neighbour pairs x 2 planes, plus `observe`.
    assert task.stats.actions == 8 * (n - 1) + 1
    # back-to-zero / back-to-360 and their re-arming for every link and plane.
    assert task.stats.events == 4 * 2 * n
    # move-increase/decrease for L2..Ln (L1 is never rotated: pruned) x 2 planes, and
    # propagate-increase/decrease for the C(n-1, 2) `affects` pairs x 2 planes.
    assert task.stats.processes == 4 * (n - 1) + 4 * comb(n - 1, 2)
    assert len(task.fluents) >= 2 * n
    assert task.init_values[task.fluent_index(f"angle(L{n},z-axis)")] is not None


def test_paper_fig7_process_as_published() -> None:
    """The paper's Fig. 7 verbatim: its `zaxis` typo is an error at the token; corrected, the
    fact the process sets is accepted with a warning."""
    fig7 = """(:process gravity-increase
:parameters (?l1 - link)
:precondition (and
    (free-to-move ?l1)
    (> (angle ?l1 z-axis) 180)
    (< (angle ?l1 z-axis) 360))
:effect (and
    (increase
        (angle ?l1 zaxis) (* #t (speed-g)))
    (increasing-angle-gravity ?l1)))"""
    head = """(define (domain fig7) (:requirements :typing :fluents :time)
(:types link plane) (:constants z-axis - plane)
(:predicates (free-to-move ?l - link) (increasing-angle-gravity ?l - link))
(:functions (angle ?l - link ?p - plane) (speed-g))
"""
    with pytest.raises(InputError) as info:
        parse_domain(head + fig7 + ")", "fig7.pddl")
    assert info.value.location is not None
    assert (info.value.location.line, info.value.location.column) == (13, 20)
    assert info.value.found == "zaxis"
    domain = parse_domain(head + fig7.replace("zaxis", "z-axis") + ")", "fig7.pddl")
    assert len(domain.warnings) == 1 and "fig7.pddl:14:5: process 'gravity-increase' sets" \
        in domain.warnings[0]
