"""PDDL+ problems: objects, facts, initial angles, speeds and the goal."""

from __future__ import annotations

import math

from artiplan.encoding.domain import domain_name
from artiplan.encoding.fall import fall_factors
from artiplan.encoding.goals import GoalSpec, fmt_number, make_goal
from artiplan.encoding.gravity import initial_gravity
from artiplan.encoding.options import EncodingOptions
from artiplan.model import ArticulatedObject, Configuration
from artiplan.model.angles import wrap_deg

#: A link the robot could not grasp: (link, ``hold`` or ``turn``, 1-based indices of what its
#: grasps met; 1 for the fixed scene and the clamped L1).
Ungraspable = tuple[str, str, frozenset[int]]


def turns_between(index: int, met: frozenset[int]) -> range:
    """1-based indices of the links whose turn moves link ``index`` relative to every link in
    ``met`` (1: the fixed scene) or some of them: the turn of link j moves links j.. against
    links ..j-1, so it separates links a < b when a < j <= b."""
    lo, hi = min(met | {index}), max(met | {index})
    return range(max(lo + 1, 2), hi + 1)


def _refusal_facts(obj: ArticulatedObject, refused: frozenset[tuple[str, str, str, str]],
                   ungraspable: frozenset[Ungraspable]) -> list[str]:
    facts = [f"(refused-{sign} {a} {b} {p})" for a, b, p, sign in sorted(refused)]
    clears: set[tuple[int, int]] = set()
    for link, role, met in sorted(ungraspable, key=lambda u: (u[0], u[1], sorted(u[2]))):
        facts.append(f"(blocked-{role} {link})")
        x = obj.index(link)
        clears |= {(j, x) for j in turns_between(x, met)}
    facts += [f"(clears {obj.links[j - 1]} {obj.links[x - 1]})" for j, x in sorted(clears)]
    return facts


def _init_facts(obj: ArticulatedObject, init: Configuration, options: EncodingOptions,
                reaching: bool = False,
                blocked: frozenset[tuple[str, str]] = frozenset(),
                refused: frozenset[tuple[str, str, str, str]] = frozenset(),
                ungraspable: frozenset[Ungraspable] = frozenset()) -> list[str]:
    facts = ["(reaching)"] if reaching and options.has_reach else []
    facts += [f"(connected {a} {b})" for a, b in obj.joints if (a, b) not in blocked]
    facts += _refusal_facts(obj, refused, ungraspable)
    if options.counts_turn:
        facts.append("(= (turned) 0)")
    facts += [f"(affects {a} {b})" for a, b in obj.affects()]
    facts += [f"(free-to-move {lk})" for lk in obj.links]
    facts += [
        f"(= (speed-i) {fmt_number(options.speed_i)})",
        f"(= (speed-d) {fmt_number(options.speed_d)})",
    ]
    if options.model == "ucm":
        facts.append(f"(= (speed-g) {fmt_number(options.speed_g)})")
    if options.torque_fall:
        facts.append(f"(tilts {options.gravity_plane})")
        facts += [f"(= (fall {lk}) {fmt_number(round(f, 3))})"
                  for lk, f in zip(obj.links, fall_factors(obj, init), strict=True)]
    if options.model == "uacm":
        facts.append(f"(= (acceleration) {fmt_number(options.acceleration)})")
    if options.has_gravity:
        # held-index 1: only the clamped base L1 is held (see encoding.domain).
        facts.append("(= (held-index) 1)")
        facts += [f"(= (link-index {lk}) {obj.index(lk)})" for lk in obj.links]
    if options.model == "uacm":
        facts += [f"(= (gravity-speed {lk}) 0)" for lk in obj.links]
    if options.has_gravity:
        facts += _gravity_flags(obj, init, options)
    if options.has_reach and options.reach_time is not None:
        facts += [f"(= (reach-time) {fmt_number(options.reach_time)})", "(= (reach-clock) 0)"]
    if options.carry == "projected":
        facts += _carry_facts(obj, init, options)
    for lk in obj.links:
        for p in options.planes:
            value = wrap_deg(init.angle(obj.index(lk), p))
            facts.append(f"(= (angle {lk} {p}) {fmt_number(value)})")
    return facts


def _gravity_flags(
    obj: ArticulatedObject, init: Configuration, options: EncodingOptions
) -> list[str]:
    """The gravity flags the initial state implies, so that no ``start-gravity-*`` event is
    enabled at time 0 (VAL refuses a problem whose initial state enables an event). With the
    hands free every link but the base feels gravity; see :func:`initial_gravity`."""
    out = []
    for lk in obj.links[1:]:
        angle = float(fmt_number(wrap_deg(init.angle(obj.index(lk), options.gravity_plane))))
        side = initial_gravity(angle, options.hysteresis)
        if side is not None:
            out.append(f"({side}-angle-gravity {lk})")
    return out


#: Below this angle from the vertical [deg] (either way) a carried link's azimuth is too
#: ill-defined for the projection: the link swings into the turning link's plane whatever its
#: azimuth says, so the paper's rule (carry 1, azimuth unchanged) is kept for it. Measured: with
#: the projection applied to a link 3 deg from hanging, the planner "turned" its azimuth by
#: 82 deg in a 27 deg turn of its neighbour (factor cot 3 deg, capped), which physics did not do.
CARRY_MIN_GAMMA = 30.0


def _carry_factors(theta_k: float, theta_j: float, gamma_j: float) -> tuple[float, float]:
    """(gamma factor, theta factor) of link j carried by a vertical turn of link k [deg in]:
    ``cos(theta_j - theta_k)`` and ``-cot(gamma_j) sin(theta_j - theta_k)``, or the rigid
    (1, 0) for a link within :data:`CARRY_MIN_GAMMA` of the vertical."""
    g = math.radians(gamma_j)
    if abs(math.sin(g)) < math.sin(math.radians(CARRY_MIN_GAMMA)):
        return 1.0, 0.0
    d = math.radians(theta_j - theta_k)
    return math.cos(d), -math.sin(d) * math.cos(g) / math.sin(g)


def _carry_facts(
    obj: ArticulatedObject, init: Configuration, options: EncodingOptions
) -> list[str]:
    """``(carry k j p)`` for every carried pair: the gamma factor on the gravity (vertical)
    plane, 1 elsewhere; and ``(carry-theta k j)``: how fast j's azimuth turns per unit
    vertical turn of k (see ``EncodingOptions.carry`` and :func:`_carry_factors`)."""
    out = []
    for a, b in obj.affects():
        i, j = obj.index(a) - 1, obj.index(b) - 1
        k_gamma, k_theta = _carry_factors(init.theta[i], init.theta[j], init.gamma[j])
        for p in options.planes:
            value = k_gamma if p == options.gravity_plane else 1.0
            out.append(f"(= (carry {a} {b} {p}) {fmt_number(round(value, 4))})")
        if options.azimuth_plane:
            out.append(f"(= (carry-theta {a} {b}) {fmt_number(round(k_theta, 4))})")
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
    reaching: bool = False,
    blocked: frozenset[tuple[str, str]] = frozenset(),
    refused: frozenset[tuple[str, str, str, str]] = frozenset(),
    ungraspable: frozenset[Ungraspable] = frozenset(),
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
        reaching: The hands are away from the object (with a reach time): the first grasp
            waits ``reach-time`` too (re-planning after a release).
        blocked: (hold link, rotated link) pairs the robot cannot grasp now: their
            ``connected`` fact is left out (the only precondition that reads it is the
            grasp's), so the plan moves the chain some other way.
        refused: (hold link, rotated link, plane, ``increase``/``decrease``) rotations the
            robot has just refused to start: the plan does not start them before some
            rotation has stopped (needs ``options.refusals``).
        ungraspable: Links the robot could not grasp in a role (:data:`Ungraspable`): no
            start grasps them that way before a turn of :func:`turns_between` has stopped
            (needs ``options.refusals``).

    Returns:
        The problem as PDDL+ text, ending with a newline.
    """
    if init.n_links != obj.n_links:
        raise ValueError(f"object has {obj.n_links} links, initial configuration {init.n_links}")
    if goal is None:
        goal = make_goal(obj, target, goal_style, seed, planes=options.planes)
    if (refused or ungraspable) and not options.refusals:
        raise ValueError("refused rotations need EncodingOptions(refusals=True)")
    if any(u[1] not in ("hold", "turn") for u in ungraspable):
        raise ValueError("an ungraspable link's role is hold or turn")
    bad = [r for r in refused if r[3] not in ("increase", "decrease")]
    if bad:
        raise ValueError(f"a refused rotation's sign is increase or decrease, not {bad[0][3]!r}")
    name = name or f"p{obj.n_links}"
    facts = "\n    ".join(_init_facts(obj, init, options, reaching, blocked, refused,
                                       ungraspable))
    return f"""(define (problem {name})
  (:domain {domain_name(options)})
  (:objects {" ".join(obj.links)} - link)
  (:init
    {facts})
  (:goal {goal.pddl(indent="    ")})
)
"""
