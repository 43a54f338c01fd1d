"""Perceived configuration -> PDDL+ problem (through the world's ontology when it has one)."""

from __future__ import annotations

from artiplan.encoding import EncodingOptions, GoalSpec, problem_pddl
from artiplan.encoding.problem import Ungraspable
from artiplan.model import ArticulatedObject, Configuration
from artiplan.model.angles import wrap_deg


def canonical(conf: Configuration) -> Configuration:
    """Each link's double-cover representation with gamma in [0, 180] (theta = azimuth).

    The PDDL+ models add a rotation's angle to every carried link's angle, which matches a rigid
    rotation of the chain only when the links' thetas are their azimuths: with gamma in
    (180, 360) a link's theta points the other way and the model turns it the wrong way.
    """
    theta, gamma = [], []
    for t, g in zip(conf.theta, conf.gamma, strict=True):
        t, g = wrap_deg(t), wrap_deg(g)
        if g > 180.0:
            t, g = wrap_deg(t + 180.0), 360.0 - g
        theta.append(t)
        gamma.append(g)
    return Configuration(tuple(theta), tuple(gamma))


def build_problem(
    obj: ArticulatedObject, perceived: Configuration, target: Configuration,
    options: EncodingOptions, goal: GoalSpec, hands_away: bool = False,
    blocked: frozenset[tuple[str, str]] = frozenset(),
    refused: frozenset[tuple[str, str, str, str]] = frozenset(),
    ungraspable: frozenset[Ungraspable] = frozenset(),
) -> str:
    """The PDDL+ problem from the perceived configuration (canonical covers) to ``goal``.

    ``hands_away`` (with a ``reach_time``): the hands are released and away from the object,
    so the first grasp also waits ``reach-time`` (gravity acts meanwhile), as after a release
    inside the plan. ``blocked``: (hold link, rotated link) pairs the robot just failed to
    grasp, planned around (see :func:`artiplan.encoding.problem_pddl`); ``refused``:
    rotations the robot has just refused, not started before the chain has moved;
    ``ungraspable``: links it could not grasp, not grasped so before they have moved relative
    to what their grasps met.
    """
    return problem_pddl(obj, canonical(perceived), target, options, goal=goal, name="replan",
                        reaching=hands_away, blocked=blocked, refused=refused,
                        ungraspable=ungraspable)
