"""Hand-built grounded tasks for the semantics tests (no parser needed).

One joint angle per task family, named like the encodings: ``(angle L2 z-axis)``.
"""

from __future__ import annotations

from artiplan.pddl.task import (
    TRUE,
    And,
    Atom,
    Comparison,
    Const,
    ContinuousEffect,
    Effect,
    FluentRef,
    GroundAction,
    GroundProcess,
    Neg,
    Not,
    NumericEffect,
    Task,
)

ANGLE, SPEED, VEL, ACC = 0, 1, 2, 3
MOVING, IN_USE, HELD, DONE = 0, 1, 2, 3
FACTS = ("(moving L2 z-axis)", "(in-use)", "(held L2)", "(done)")
FLUENTS = ("(angle L2 z-axis)", "(speed-i)", "(vel L2)", "(acceleration)")


def f(i: int) -> FluentRef:
    return FluentRef(i)


def c(v: float) -> Const:
    return Const(v)


def wrap_events(low: Comparison | None = None) -> tuple[GroundAction, ...]:
    """back-to-zero (>= 360: -360) and back-to-360 (<= -0.01: +360) on the angle.

    ``low`` replaces back-to-360's precondition (``(< angle 0)`` makes VAL's slack bounce).
    """
    to_zero = GroundAction(
        "back-to-zero", ("L2", "z-axis"), Comparison(">=", f(ANGLE), c(360.0)),
        Effect(numeric=(NumericEffect("decrease", ANGLE, c(360.0)),)), kind="event",
    )
    to_360 = GroundAction(
        "back-to-360", ("L2", "z-axis"),
        low if low is not None else Comparison("<=", f(ANGLE), c(-0.01)),
        Effect(numeric=(NumericEffect("increase", ANGLE, c(360.0)),)), kind="event",
    )
    return to_zero, to_360


def rotation_actions() -> tuple[GroundAction, ...]:
    start = GroundAction(
        "start-increase", ("L1", "L2", "z-axis"), Not(Atom(IN_USE)),
        Effect(add=(IN_USE, MOVING)),
    )
    stop = GroundAction(
        "stop-increase", ("L1", "L2", "z-axis"), Atom(MOVING),
        Effect(delete=(IN_USE, MOVING)),
    )
    observe = GroundAction("observe", (), TRUE, Effect())
    return start, stop, observe


def ng_task(angle0: float = 355.0, speed: float = 10.0, goal=None,
            extra_events: tuple[GroundAction, ...] = (),
            wraps: tuple[GroundAction, ...] | None = None) -> Task:
    """NG: the robot rotates the angle at a constant speed; it wraps at 360."""
    move = GroundProcess(
        "move-increase", ("L2", "z-axis"), Atom(MOVING),
        (ContinuousEffect(ANGLE, f(SPEED)),),
    )
    return Task(
        "ng", "p", FACTS, FLUENTS, frozenset(), (angle0, speed, 0.0, 0.0),
        goal if goal is not None else TRUE, rotation_actions(),
        (wrap_events() if wraps is None else wraps) + extra_events,
        (move,),
    )


def uacm_task(angle0: float = 90.0, acc: float = 2.0, threshold: float = 45.0) -> Task:
    """UACM: gravity pulls the free angle down from rest with constant angular acceleration.

    ``fall`` (angle in (0, 180), not held): d angle = -vel, d vel = acc; event ``landed`` when
    the angle drops to ``threshold`` or below: sets (done). ``grab`` holds the link (stops the
    fall) and an event resets vel to 0 once held.
    """
    free = And((Not(Atom(HELD)), Comparison(">", f(ANGLE), c(0.0)),
                Comparison("<", f(ANGLE), c(180.0))))
    fall = GroundProcess("gravity-decrease", ("L2",), free,
                         (ContinuousEffect(ANGLE, Neg(f(VEL))),))
    accel = GroundProcess("accelerate", ("L2",), free, (ContinuousEffect(VEL, f(ACC)),))
    landed = GroundAction("landed", ("L2",), And((
        Comparison("<=", f(ANGLE), c(threshold)), Not(Atom(DONE)))),
        Effect(add=(DONE,)), kind="event")
    # (not (= vel 0)), not (> vel 0): VAL's slack would re-trigger a strict one after vel := 0.
    reset = GroundAction("reset-speed", ("L2",),
                         And((Atom(HELD), Not(Comparison("=", f(VEL), c(0.0))))),
                         Effect(numeric=(NumericEffect("assign", VEL, c(0.0)),)), kind="event")
    grab = GroundAction("grab", ("L2",), Not(Atom(HELD)), Effect(add=(HELD,)))
    observe = GroundAction("observe", (), TRUE, Effect())
    return Task(
        "uacm", "p", FACTS, FLUENTS, frozenset(), (angle0, 10.0, 0.0, acc),
        Atom(DONE), (grab, observe), (landed, reset), (fall, accel),
    )


#: A water tank (PDDL text): a process fills it, an overflow event halves the surplus.
TANK = """
(define (domain tank)
  (:requirements :strips :numeric-fluents :time)
  (:predicates (filling))
  (:functions (level) (flow-rate))
  (:action open :parameters () :precondition (not (filling)) :effect (filling))
  (:action close :parameters () :precondition (filling) :effect (not (filling)))
  (:process fill :parameters () :precondition (filling)
    :effect (increase (level) (* #t (flow-rate))))
  (:event overflow :parameters () :precondition (>= (level) 10)
    :effect (and (decrease (level) 5) (increase (flow-rate) 1))))
"""
TANK_PROBLEM = """
(define (problem t1) (:domain tank)
  (:init (= (level) 7) (= (flow-rate) 2))
  (:goal (> (level) 6.5)))
"""
