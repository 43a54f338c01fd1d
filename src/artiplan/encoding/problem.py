"""PDDL+ problems: objects, facts, initial angles, speeds and the goal."""

from __future__ import annotations

from artiplan.encoding.domain import domain_name
from artiplan.encoding.goals import GoalSpec, fmt_number, make_goal
from artiplan.encoding.options import EncodingOptions
from artiplan.model import ArticulatedObject, Configuration
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
    for lk in obj.links:
        for p in options.planes:
            value = wrap_deg(init.angle(obj.index(lk), p))
            facts.append(f"(= (angle {lk} {p}) {fmt_number(value)})")
    return facts


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
