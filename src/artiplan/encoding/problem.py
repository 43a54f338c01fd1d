"""PDDL+ problems: objects, facts, initial angles, speeds and the goal."""

from __future__ import annotations

import math

from artiplan.encoding.domain import domain_name
from artiplan.encoding.goals import GoalSpec, fmt_number, make_goal
from artiplan.encoding.options import EncodingOptions
from artiplan.model import HORIZONTAL_PLANE, ArticulatedObject, Configuration
from artiplan.model.angles import wrap_deg


def _init_facts(obj: ArticulatedObject, init: Configuration, options: EncodingOptions) -> list[str]:
    facts = [f"(connected {a} {b})" for a, b in obj.joints]
    facts += [f"(affects {a} {b})" for a, b in obj.affects()]
    facts += [f"(free-to-move {lk})" for lk in obj.links]
    facts += [
        f"(= (speed-i) {fmt_number(options.speed_i)})",
        f"(= (speed-d) {fmt_number(options.speed_d)})",
    ]
    if options.model == "ucm":
        facts.append(f"(= (speed-g) {fmt_number(options.speed_g)})")
    if options.model == "uacm":
        facts.append(f"(= (acceleration) {fmt_number(options.acceleration)})")
    if options.has_gravity:
        # held-index 1: only the clamped base L1 is held (see encoding.domain).
        facts.append("(= (held-index) 1)")
        facts += [f"(= (link-index {lk}) {obj.index(lk)})" for lk in obj.links]
    if options.model == "uacm":
        facts += [f"(= (gravity-speed {lk}) 0)" for lk in obj.links]
    if options.reach_time is not None:
        facts += [f"(= (reach-time) {fmt_number(options.reach_time)})", "(= (reach-clock) 0)"]
    if options.carry == "projected":
        facts += _carry_facts(obj, init, options)
    for lk in obj.links:
        for p in options.planes:
            value = wrap_deg(init.angle(obj.index(lk), p))
            facts.append(f"(= (angle {lk} {p}) {fmt_number(value)})")
    return facts


#: Largest |d theta_j / d phi| of the projected carry (cot 18 deg): near the vertical a link's
#: azimuth swings fast but its direction hardly moves.
CARRY_THETA_CAP = 3.0


def _carry_facts(
    obj: ArticulatedObject, init: Configuration, options: EncodingOptions
) -> list[str]:
    """``(carry k j p)`` for every carried pair: ``cos(theta_j - theta_k)`` on the gravity
    (vertical) plane, 1 elsewhere; and ``(carry-theta k j)``: how fast j's azimuth turns per
    unit vertical turn of k (see ``EncodingOptions.carry``)."""
    out = []
    for a, b in obj.affects():
        for p in options.planes:
            if p == options.gravity_plane:
                d = init.theta[obj.index(b) - 1] - init.theta[obj.index(a) - 1]
                value = round(math.cos(math.radians(d)), 4)
            else:
                value = 1.0
            out.append(f"(= (carry {a} {b} {p}) {fmt_number(value)})")
        if options.gravity_plane != HORIZONTAL_PLANE and HORIZONTAL_PLANE in options.planes:
            # d theta_j / d phi = -cot(gamma_j) sin(theta_j - theta_k) per unit turn of k
            # (capped: theta is ill-defined for a nearly vertical link).
            d = math.radians(init.theta[obj.index(b) - 1] - init.theta[obj.index(a) - 1])
            g = math.radians(init.gamma[obj.index(b) - 1])
            s, c = math.sin(g), math.cos(g)
            factor = -math.sin(d) * c / s if abs(s) > 1e-9 else 0.0
            factor = max(-CARRY_THETA_CAP, min(CARRY_THETA_CAP, factor))
            out.append(f"(= (carry-theta {a} {b}) {fmt_number(round(factor, 4))})")
    return out


def problem_pddl(
    obj: ArticulatedObject,
    init: Configuration,
    target: Configuration,
    options: EncodingOptions,
    goal_style: str = "threshold",
    seed: int = 0,
    name: str | None = None,
    goal: GoalSpec | None = None,
) -> str:
    """The PDDL+ problem text that takes ``obj`` from ``init`` to ``target``.

    Args:
        obj: The object (its links become the problem's objects).
        init: Initial configuration [deg]; angles are written wrapped to [0, 360).
        target: Target configuration [deg].
        options: Encoding options (model, speeds, planes) - the same as the domain's.
        goal_style: ``threshold`` (paper) or ``window``; see :func:`make_goal`.
        seed: Seed of the goal's random choice (threshold style's upper bound).
        name: Problem name (default ``p<n>``).
        goal: A ready goal, overriding ``goal_style``/``seed`` when given.

    Returns:
        The problem as PDDL+ text, ending with a newline.
    """
    if init.n_links != obj.n_links:
        raise ValueError(f"object has {obj.n_links} links, initial configuration {init.n_links}")
    if goal is None:
        goal = make_goal(obj, target, goal_style, seed, planes=options.planes)
    name = name or f"p{obj.n_links}"
    facts = "\n    ".join(_init_facts(obj, init, options))
    return f"""(define (problem {name})
  (:domain {domain_name(options)})
  (:objects {" ".join(obj.links)} - link)
  (:init
    {facts})
  (:goal {goal.pddl(indent="    ")})
)
"""
