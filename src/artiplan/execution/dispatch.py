"""Carry out one plan action on the world (the paper's action vocabulary -> hand commands)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from artiplan.model import PLANES, ArticulatedObject, Configuration
from artiplan.semantics import TimedAction

if TYPE_CHECKING:
    from artiplan.world import World


class ActionFailed(RuntimeError):
    """The world could not carry out an action (unknown action, unreachable grasp, IK failure)."""


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


def dispatch(
    world: World, action: TimedAction, speeds: tuple[float, float], predicted: Configuration,
    duration: float | None = None,
) -> str:
    """Carry out ``action`` now; returns a one-line description of what the hands did.

    ``start-increase/decrease L_k L_k+1 p``: hold L_k, rotate L_k+1 on plane p at
    ``speeds`` (increase, decrease) [deg/s], in the representation of ``predicted``; the
    hands choose grasps that can keep turning for ``duration`` [s] (the plan's time to its
    stop; None: the world's default extent). ``stop-*``: stop and release both hands.
    ``observe``: nothing. Raises :class:`ActionFailed` when the world cannot do it (out of
    reach, or no collision-free way to do it).
    """
    name = action.name.lower()
    if name == "observe":
        return "observe"
    if name.startswith("stop-"):
        world.stop(release=True)
        return "stop and release"
    if name in ("start-increase", "start-decrease") and len(action.args) == 3:
        hold, turn = link_named(world.obj, action.args[0]), link_named(world.obj, action.args[1])
        plane = _plane(action.args[2])
        direction = 1 if name == "start-increase" else -1
        speed = speeds[0] if direction > 0 else speeds[1]
        extent = None if duration is None else speed * duration
        try:
            world.hold_and_rotate(hold, turn, plane, direction, speed, reference=predicted,
                                  extent_deg=extent)
        except (ValueError, RuntimeError, FloatingPointError) as exc:
            raise ActionFailed(f"{action.signature}: {exc}") from exc
        sign = "+" if direction > 0 else "-"
        limit = getattr(world, "turn_limit", None)
        note = (f" (stops after {limit[0]:.0f} of {extent:.0f} deg: {limit[1]})"
                if limit is not None and extent is not None else "")
        return f"hold {hold}, rotate {turn} on {plane} {sign}{speed:g} deg/s{note}"
    raise ActionFailed(f"no hand command for {action.signature}")


def planned_duration(actions: list[TimedAction], start: TimedAction) -> float | None:
    """Time [s] from ``start`` (a ``start-*`` action) to its ``stop-*`` (same arguments) in
    ``actions``; None if the plan never stops it."""
    name = start.name.lower()
    if not name.startswith("start-"):
        return None
    stop = "stop-" + name[len("start-"):]
    args = [a.lower() for a in start.args]
    for a in sorted(actions, key=lambda x: x.time):
        if a.time >= start.time and a.name.lower() == stop and [x.lower() for x in a.args] == args:
            return float(a.time - start.time)
    return None
