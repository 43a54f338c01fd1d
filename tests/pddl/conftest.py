"""Small hand-written PDDL+ files shared by the pddl tests."""

from __future__ import annotations

from pathlib import Path

import pytest

#: A UCM-like domain in the paper's style (Fig. 6-7): `?l1 -link` without a space, a process
#: that sets a fact (the paper's quirk), static `connected`/`affects`, static speeds.
ARM_DOMAIN = """; a small UCM-like domain
(define (domain ARTI)
 (:requirements :typing :fluents :time :negative-preconditions)
 (:types link plane)
 (:constants z-axis - plane)
 (:predicates (connected ?l1 ?l2 -link) (affects ?l1 ?l2 - link) (in-use)
   (free-to-move ?l - link) (increasing-angle-robot ?l - link ?x - plane)
   (increasing-angle-gravity ?l - link))
 (:functions (angle ?l - link ?x - plane) - number (speed-i) (speed-g))
 (:action start-increase
  :parameters (?l1 -link ?l2 -link ?x -plane)
  :precondition (and (connected ?l1 ?l2) (not (in-use)))
  :effect (and (in-use) (not (free-to-move ?l2)) (not (free-to-move ?l1))
     (increasing-angle-robot ?l2 ?x)))
 (:action stop-increase
  :parameters (?l1 ?l2 - link ?x - plane)
  :precondition (and (connected ?l1 ?l2) (increasing-angle-robot ?l2 ?x))
  :effect (and (not (in-use)) (free-to-move ?l2) (free-to-move ?l1)
     (not (increasing-angle-robot ?l2 ?x))))
 (:process move-increase
  :parameters (?l - link ?x - plane)
  :precondition (increasing-angle-robot ?l ?x)
  :effect (increase (angle ?l ?x) (* #t (speed-i))))
 (:process propagate
  :parameters (?l1 ?l2 - link ?x - plane)
  :precondition (and (affects ?l1 ?l2) (increasing-angle-robot ?l1 ?x))
  :effect (increase (angle ?l2 ?x) (* (speed-i) #t)))
 (:process gravity-increase
  :parameters (?l1 - link)
  :precondition (and (free-to-move ?l1) (> (angle ?l1 z-axis) 180) (< (angle ?l1 z-axis) 360))
  :effect (and (increase (angle ?l1 z-axis) (* #t (speed-g))) (increasing-angle-gravity ?l1)))
 (:event back-to-zero
  :parameters (?l3 -link ?x -plane)
  :precondition (>= (angle ?l3 ?x) 360)
  :effect (assign (angle ?l3 ?x) 0))
)
"""

ARM_PROBLEM = """(define (problem p1) (:domain arti)
 (:objects L1 L2 L3 - link xy-axes - plane)
 (:init (connected L1 L2) (connected l2 L3) (affects L2 L3) (free-to-move L2) (free-to-move L3)
  (= (speed-i) 10) (= (speed-g) .5)
  (= (angle L1 xy-axes) 0) (= (angle L1 z-axis) 0)
  (= (angle L2 xy-axes) 0) (= (angle L2 z-axis) -3)
  (= (angle L3 xy-axes) 1e-3) (= (angle L3 z-axis) 0)
  (= (foo) 3))
 (:goal (and (> (angle L2 xy-axes) 265.4) (< (angle L3 z-axis) 5.5))))
"""


@pytest.fixture
def arm_domain() -> str:
    return ARM_DOMAIN


@pytest.fixture
def arm_problem() -> str:
    return ARM_PROBLEM


@pytest.fixture(scope="session")
def suite_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The project's 240-problem suite, written by ``artiplan.encoding.write_suite``."""
    from artiplan.encoding import write_suite

    out = tmp_path_factory.mktemp("suite")
    write_suite(out)
    return out
