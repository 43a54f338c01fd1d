"""A plan's actions as typed steps, mapped once, and carrying a step out on the world.

:func:`plan_steps` reads the paper's action vocabulary once per plan: ``start-increase`` /
``start-decrease L_k L_k+1 p`` is a :class:`Rotate` (hold L_k, turn L_k+1 on plane p, with the
plan's time to its stop), ``stop-*`` a :class:`Stop`, ``observe`` an :class:`Observe`;
anything else is an :class:`Unknown` step that fails when dispatched. :func:`dispatch` turns a
step into hand commands.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from artiplan.model import PLANES, ArticulatedObject, Configuration
from artiplan.semantics import Plan, TimedAction

if TYPE_CHECKING:
    from artiplan.world import World


class ActionFailed(RuntimeError):
    """The world could not carry out an action (unknown action, unreachable grasp, IK failure).

    Attributes:
        arms_caught: The grasps were fine but no arm motion to them was found from where the
            arms are (:class:`artiplan.world.pairs.NoArmMotionError`): from home it may work.
        blocked: Links no hand can grasp now in their role, and the indices of what their
            grasps met (:attr:`artiplan.world.pairs.NotExecutableError.blocked`).
    """

    def __init__(self, message: str, arms_caught: bool = False,
                 blocked: tuple[tuple[str, str, frozenset[int]], ...] = ()) -> None:
        super().__init__(message)
        self.arms_caught = arms_caught
        self.blocked = blocked


@dataclass(frozen=True)
class Rotate:
    """Hold ``hold``, turn ``turn`` on ``plane`` (``direction`` +1 increases the angle) until
    the plan's stop ``duration`` [s] later (None: the plan never stops it)."""

    action: TimedAction
    hold: str
    turn: str
    plane: str
    direction: int
    duration: float | None


@dataclass(frozen=True)
class Stop:
    """Stop turning and release both hands."""

    action: TimedAction


@dataclass(frozen=True)
class Observe:
    """Nothing to do (the plan's end marker)."""

    action: TimedAction


@dataclass(frozen=True)
class Unknown:
    """An action the hands cannot do (``reason``)."""

    action: TimedAction
    reason: str


Step = Rotate | Stop | Observe | Unknown


def link_named(obj: ArticulatedObject, name: str) -> str:
    """The object's link called ``name`` (any case); :class:`ActionFailed` if none."""
    for lk in obj.links:
        if lk.lower() == name.lower():
            return lk
    raise ActionFailed(f"unknown link {name!r}")


def _plane(name: str) -> str:
    for p in PLANES:
        if p.lower() == name.lower():
            return p
    raise ActionFailed(f"unknown plane {name!r}")


def plan_steps(plan: Plan, obj: ArticulatedObject) -> list[Step]:
    """The plan's actions, in time order, as steps (module docstring)."""
    actions = sorted(plan.actions, key=lambda a: a.time)
    steps: list[Step] = []
    for k, a in enumerate(actions):
        name = a.name.lower()
        if name == "observe":
            steps.append(Observe(a))
        elif name.startswith("stop-"):
            steps.append(Stop(a))
        elif name in ("start-increase", "start-decrease") and len(a.args) == 3:
            try:
                hold, turn = link_named(obj, a.args[0]), link_named(obj, a.args[1])
                plane = _plane(a.args[2])
            except ActionFailed as exc:
                steps.append(Unknown(a, str(exc)))
                continue
            stop = "stop-" + name[len("start-"):]
            args = [x.lower() for x in a.args]
            end = next((b.time for b in actions[k + 1:]
                        if b.name.lower() == stop and [x.lower() for x in b.args] == args), None)
            steps.append(Rotate(a, hold, turn, plane, 1 if name == "start-increase" else -1,
                                None if end is None else float(end - a.time)))
        else:
            steps.append(Unknown(a, f"no hand command for {a.signature}"))
    return steps


def dispatch(
    world: World, step: Step, speeds: tuple[float, float], predicted: Configuration
) -> str:
    """Carry out ``step`` now; returns a one-line description of what the hands did.

    A :class:`Rotate` turns at ``speeds`` (increase, decrease) [deg/s], in the representation
    of ``predicted``; the hands choose grasps that can keep turning for the step's duration.
    Raises :class:`ActionFailed` when the world cannot do it (out of reach, or no
    collision-free way to do it).
    """
    if isinstance(step, Observe):
        return "observe"
    if isinstance(step, Stop):
        world.stop(release=True)
        return "stop and release"
    if isinstance(step, Unknown):
        raise ActionFailed(step.reason)
    speed = speeds[0] if step.direction > 0 else speeds[1]
    extent = None if step.duration is None else speed * step.duration
    return rotate(world, step, speed, predicted, extent)


def rotate(
    world: World, step: Rotate, speed: float, predicted: Configuration, extent: float | None
) -> str:
    """Grasp and start turning as ``step`` says, at ``speed`` [deg/s], for ``extent`` [deg]
    (None: open-ended); the line :func:`dispatch` returns. Also the re-grasp that resumes a
    turn the arms had to stop short (:mod:`artiplan.execution.loop`)."""
    try:
        world.hold_and_rotate(step.hold, step.turn, step.plane, step.direction, speed,
                              reference=predicted, extent_deg=extent)
    except (ValueError, RuntimeError) as exc:  # not FloatingPointError: the physics diverged
        raise ActionFailed(f"{step.action.signature}: {exc}",
                           bool(getattr(exc, "arms_caught", False)),
                           tuple(getattr(exc, "blocked", ()))) from exc
    sign = "+" if step.direction > 0 else "-"
    limit = getattr(world, "turn_limit", None)
    note = (f" (stops after {limit[0]:.0f} of {extent:.0f} deg: {limit[1]})"
            if limit is not None and extent is not None else "")
    return f"hold {step.hold}, rotate {step.turn} on {step.plane} {sign}{speed:g} deg/s{note}"
