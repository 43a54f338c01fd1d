"""The paper's UCM model of a suite task, built with unified-planning's Python API (no PDDL text).

It mirrors ``artiplan.encoding`` for ``model="ucm"`` (default speeds, rigid carry, no reach
time): the same types, fluents, actions, processes and events, and the same initial values and
goal (from ``artiplan.encoding.make_goal``), so that a plan for it is a plan for the encoding's
PDDL+ text too (tests/up/test_up_ucm.py checks both ways).
"""

from __future__ import annotations

from fractions import Fraction

from unified_planning.model import Event, Fluent, InstantaneousAction, Object, Problem, Process
from unified_planning.shortcuts import GT, LE, LT, And, BoolType, Not, Plus, RealType, UserType

from artiplan.encoding import make_goal
from artiplan.encoding.suite import SuiteTask
from artiplan.model import PLANES, ArticulatedObject
from artiplan.model.angles import wrap_deg

SPEED = 10.0  # deg/s, speed-i = speed-d


def ucm_problem(task: SuiteTask, speed_g: float = 0.1) -> Problem:
    """The UCM problem of ``task`` (threshold goal, seeded as the suite seeds it)."""
    obj = ArticulatedObject(task.size)
    link, plane = UserType("link"), UserType("plane")
    f = _fluents(link, plane)
    pb = Problem(f"ucm-{task.name}")
    for fl in f.values():
        pb.add_fluent(fl, default_initial_value=False if fl.type.is_bool_type() else None)
    planes = {p: Object(p, plane) for p in PLANES}
    links = {lk: Object(lk, link) for lk in obj.links}
    pb.add_objects([*planes.values(), *links.values()])
    for op in (*_robot(f, link, plane), *_wrap(f, link, plane),
               *_gravity(f, link, planes["z-axis"])):
        if isinstance(op, Process):
            pb.add_process(op)
        elif isinstance(op, Event):
            pb.add_event(op)
        else:
            pb.add_action(op)
    pb.add_action(InstantaneousAction("observe"))
    _initial(pb, f, obj, task, links, planes, speed_g)
    goal = make_goal(obj, task.target, "threshold", task.seed, planes=PLANES)
    for c in goal.conditions:
        angle = f["angle"](links[c.link], planes[c.plane])
        value = _exact(c.value)
        pb.add_goal(GT(angle, value) if c.op == ">" else LT(angle, value))
    return pb


def _fluents(link: UserType, plane: UserType) -> dict[str, Fluent]:
    b, r = BoolType(), RealType()
    return {
        "in-use": Fluent("in-use", b),
        "free-to-move": Fluent("free-to-move", b, l=link),
        "connected": Fluent("connected", b, l1=link, l2=link),
        "affects": Fluent("affects", b, l1=link, l2=link),
        "increasing-angle-robot": Fluent("increasing-angle-robot", b, l=link, p=plane),
        "decreasing-angle-robot": Fluent("decreasing-angle-robot", b, l=link, p=plane),
        "angle": Fluent("angle", r, l=link, p=plane),
        "speed-i": Fluent("speed-i", r),
        "speed-d": Fluent("speed-d", r),
        "link-index": Fluent("link-index", r, l=link),
        "held-index": Fluent("held-index", r),
        "speed-g": Fluent("speed-g", r),
    }


def _robot(f: dict[str, Fluent], link: UserType, plane: UserType) -> list[object]:
    ops: list[object] = []
    for way, speed, sign in (("increase", "speed-i", 1), ("decrease", "speed-d", -1)):
        moving = f[f"{way[:-1]}ing-angle-robot"]
        start = InstantaneousAction(f"start-{way}", l1=link, l2=link, p=plane)
        l1, l2, p = start.parameters
        start.add_precondition(f["connected"](l1, l2))
        start.add_precondition(Not(f["in-use"]()))
        start.add_effect(f["in-use"](), True)
        start.add_effect(f["free-to-move"](l1), False)
        start.add_effect(f["free-to-move"](l2), False)
        start.add_effect(moving(l2, p), True)
        start.add_effect(f["held-index"](), f["link-index"](l2))
        stop = InstantaneousAction(f"stop-{way}", l1=link, l2=link, p=plane)
        l1, l2, p = stop.parameters
        stop.add_precondition(f["connected"](l1, l2))
        stop.add_precondition(moving(l2, p))
        stop.add_effect(f["in-use"](), False)
        stop.add_effect(f["free-to-move"](l1), True)
        stop.add_effect(f["free-to-move"](l2), True)
        stop.add_effect(moving(l2, p), False)
        stop.add_effect(f["held-index"](), 1)
        move = Process(f"move-{way}", l=link, p=plane)
        lk, p = move.parameters
        move.add_precondition(moving(lk, p))
        _rate(move, f["angle"](lk, p), f[speed](), sign)
        carry = Process(f"propagate-{way}", l1=link, l2=link, p=plane)
        l1, l2, p = carry.parameters
        carry.add_precondition(moving(l1, p))
        carry.add_precondition(f["affects"](l1, l2))
        _rate(carry, f["angle"](l2, p), f[speed](), sign)
        ops += [start, stop, move, carry]
    return ops


def _rate(proc: Process, fluent: object, rate: object, sign: int) -> None:
    if sign > 0:
        proc.add_increase_continuous_effect(fluent, rate)
    else:
        proc.add_decrease_continuous_effect(fluent, rate)


def _wrap(f: dict[str, Fluent], link: UserType, plane: UserType) -> list[Event]:
    up = Event("back-to-zero", l=link, p=plane)
    lk, p = up.parameters
    up.add_precondition(LE(360, f["angle"](lk, p)))
    up.add_effect(f["angle"](lk, p), 0)
    down = Event("back-to-360", l=link, p=plane)
    lk, p = down.parameters
    down.add_precondition(LE(f["angle"](lk, p), Fraction("-0.01")))
    down.add_effect(f["angle"](lk, p), Fraction("359.99"))
    return [up, down]


def _gravity(f: dict[str, Fluent], link: UserType, z: Object) -> list[Process]:
    ops = []
    for way, lo, hi, sign in (("decrease", 0, 180, -1), ("increase", 180, 360, 1)):
        fall = Process(f"gravity-{way}", l=link)
        (lk,) = fall.parameters
        fall.add_precondition(_feels(f, lk, z, lo, hi))
        _rate(fall, f["angle"](lk, z), f["speed-g"](), sign)
        carry = Process(f"propagate-gravity-{way}", l1=link, l2=link)
        l1, l2 = carry.parameters
        carry.add_precondition(And(f["affects"](l1, l2), _feels(f, l1, z, lo, hi)))
        _rate(carry, f["angle"](l2, z), f["speed-g"](), sign)
        ops += [fall, carry]
    return ops


def _feels(f: dict[str, Fluent], lk: object, z: Object, lo: float, hi: float) -> object:
    return And(GT(f["link-index"](lk), Plus(f["held-index"](), Fraction(1, 2))),
               GT(f["angle"](lk, z), lo), LT(f["angle"](lk, z), hi))


def _initial(pb: Problem, f: dict[str, Fluent], obj: ArticulatedObject, task: SuiteTask,
             links: dict[str, Object], planes: dict[str, Object], speed_g: float) -> None:
    for a, b in obj.joints:
        pb.set_initial_value(f["connected"](links[a], links[b]), True)
    for a, b in obj.affects():
        pb.set_initial_value(f["affects"](links[a], links[b]), True)
    for lk in obj.links:
        pb.set_initial_value(f["free-to-move"](links[lk]), True)
        pb.set_initial_value(f["link-index"](links[lk]), obj.index(lk))
        for p in PLANES:
            value = _exact(wrap_deg(task.initial.angle(obj.index(lk), p)))
            pb.set_initial_value(f["angle"](links[lk], planes[p]), value)
    pb.set_initial_value(f["speed-i"](), SPEED)
    pb.set_initial_value(f["speed-d"](), SPEED)
    pb.set_initial_value(f["speed-g"](), _exact(speed_g))
    pb.set_initial_value(f["held-index"](), 1)


def _exact(x: float) -> Fraction:
    """``x`` [deg] as the encoding writes it (6 decimals), exactly (a float is binary)."""
    return Fraction(f"{round(x, 6):.6f}")
