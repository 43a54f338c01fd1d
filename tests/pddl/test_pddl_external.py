"""Files in the style of the public PDDL+ benchmarks (ENHSP's linear car and generator), with
their formatting habits: `:parameters()`, `(:metric minimize(total-time))`, rates that are
fluents or non-linear expressions."""

from __future__ import annotations

from artiplan.pddl import load_task, parse_domain, parse_problem, write_domain, write_problem
from artiplan.pddl.task import (
    And,
    Atom,
    BinOp,
    Comparison,
    Const,
    ContinuousEffect,
    FluentRef,
    Metric,
    NumericEffect,
)

CAR = """(define (domain car_linear_mt_sc)
(:requirements :typing :durative-actions :fluents :time :negative-preconditions
  :timed-initial-literals)
(:predicates (running) (engineBlown) (transmission_fine) (goal_reached) )
(:functions (d) (v) (a) (up_limit) (down_limit) (running_time) )
(:process moving
:parameters ()
:precondition (and (running))
:effect (and (increase (v) (* #t (a)))
             (increase (d) (* #t (v)))
\t     (increase (running_time) (* #t 1))
)
)
(:action accelerate
  :parameters()
  :precondition (and (running) (< (a) (up_limit)))
  :effect (and (increase (a) 1))
)
(:action decelerate
  :parameters()
  :precondition (and (running) (> (a) (down_limit)))
  :effect (and (decrease (a) 1))
)
(:event engineExplode
:parameters ()
:precondition (and (running) (>= (a) 1) (>= (v) 100))
:effect (and (not (running)) (engineBlown) (assign (a) 0))
)
(:action stop
:parameters()
:precondition(and (= (v) 0) (>= (d) 30) (not (engineBlown)) )
:effect(goal_reached)
)
)
"""

CAR_PROBLEM = """(define (problem car_prob)
    (:domain car_linear_mt_sc)
    (:init
        (running)
        (transmission_fine)
        (= (running_time) 0)
        (= (up_limit) 1)
        (= (down_limit) -1)
        (= (d) 0)
        (= (a) 0)
        (= (v) 0)
    )
    (:goal (and (goal_reached) ))
    (:metric minimize(total-time))
)
"""

GENERATOR = """(define (domain generator)
(:requirements :fluents :time :typing)
(:types generator tank)
(:predicates (generator-ran) (available ?t - tank) (using ?t - tank) (refueling ?g - generator))
(:functions (fuelLevel ?g - generator) (capacity ?g - generator) (ptime ?t - tank))
(:action generate :parameters (?g - generator) :precondition ()
 :effect (generator-ran))
(:process generating :parameters (?g - generator) :precondition (generator-ran)
 :effect (decrease (fuelLevel ?g) (* #t 1)))
(:action refuel :parameters (?g - generator ?t - tank)
 :precondition (and (available ?t))
 :effect (and (using ?t) (not (available ?t))))
(:process refuelling :parameters (?g - generator ?t - tank)
 :precondition (and (using ?t))
 :effect (and (decrease (ptime ?t) (* #t 1))
   (increase (fuelLevel ?g) (* #t (* 0.1 (* (- 10 (ptime ?t)) (- 10 (ptime ?t))))))))
(:event tankEmpty :parameters (?t - tank) :precondition (and (using ?t) (<= (ptime ?t) 0))
 :effect (not (using ?t))))
"""

GENERATOR_PROBLEM = """(define (problem run-generator)
 (:domain generator)
 (:objects gen - generator tank1 tank2 - tank)
 (:init (= (fuelLevel gen) 1000) (= (capacity gen) 1600)
  (available tank1) (available tank2) (= (ptime tank1) 10) (= (ptime tank2) 10))
 (:goal (and (generator-ran) (<= (fuelLevel gen) (capacity gen)))))
"""


def test_linear_car() -> None:
    domain = parse_domain(CAR, "car.pddl")
    assert any(":durative-actions is declared but not used" in w for w in domain.warnings)
    task = load_task(CAR, CAR_PROBLEM)
    f = task.fluent_index
    moving = task.processes[0]
    assert moving.continuous == (
        ContinuousEffect(f("(v)"), FluentRef(f("(a)"))),
        ContinuousEffect(f("(d)"), FluentRef(f("(v)"))),
        ContinuousEffect(f("(running_time)"), Const(1.0)),
    )
    accelerate = task.action_by_signature("(accelerate)")
    # (up_limit) is static: folded; (running) is deleted by the event, so it stays a fact.
    assert accelerate.precondition == And((Atom(task.fact_index("(running)")),
                                           Comparison("<", FluentRef(f("(a)")), Const(1.0))))
    assert accelerate.effect.numeric == (NumericEffect("increase", f("(a)"), Const(1.0)),)
    assert task.metric == Metric("minimize", None, uses_total_time=True)
    assert [e.signature for e in task.events] == ["(engineExplode)"]
    assert task.fluents == ("(running_time)", "(d)", "(a)", "(v)")  # init order, statics out
    assert parse_problem(write_problem(parse_problem(CAR_PROBLEM))) == parse_problem(CAR_PROBLEM)


def test_generator_nonlinear_rate() -> None:
    task = load_task(GENERATOR, GENERATOR_PROBLEM)
    f = task.fluent_index
    refuel = next(p for p in task.processes if p.signature == "(refuelling gen tank1)")
    ptime = FluentRef(f("(ptime tank1)"))
    ten_minus = BinOp("-", Const(10.0), ptime)
    assert refuel.continuous == (
        ContinuousEffect(f("(ptime tank1)"), Const(-1.0)),  # decrease: the rate negated
        ContinuousEffect(f("(fuelLevel gen)"),
                         BinOp("*", Const(0.1), BinOp("*", ten_minus, ten_minus))),
    )
    # (capacity gen) is static: the goal compares with the constant.
    assert task.goal == And((Atom(task.fact_index("(generator-ran)")),
                             Comparison("<=", FluentRef(f("(fuelLevel gen)")), Const(1600.0))))
    tree = parse_domain(GENERATOR)
    assert parse_domain(write_domain(tree)) == tree
