"""Which links gravity acts on (shared/docs/conventions.md), as plain Python.

The PDDL+ domains encode the same rule with ``(link-index ?l) > (held-index) + 0.5``; this
function states it directly, for tests, the physics world and the fidelity measurements.
"""

from __future__ import annotations

from collections.abc import Iterable

from artiplan.model import ArticulatedObject
from artiplan.tolerances import VAL_SLACK


def gravity_links(obj: ArticulatedObject, held: Iterable[str] = ()) -> tuple[str, ...]:
    """Links that feel gravity while the links ``held`` are held.

    A link l_j feels gravity when j >= 2 (L1 is clamped), it is not held, and no held link is
    tip-ward of it (a held link tip-ward would close the chain through the clamped base).

    Args:
        obj: The object.
        held: Names of the held links (e.g. ``("L2", "L3")``: hold L2, rotate L3).

    Returns:
        Link names, base to tip.
    """
    held_indices = [obj.index(lk) for lk in held]
    outermost = max(held_indices, default=1)
    return tuple(lk for lk in obj.links if obj.index(lk) > max(outermost, 1))


def initial_gravity(gamma: float, margin: float) -> str | None:
    """Which way gravity turns a free link whose vertical angle is ``gamma`` [deg, in
    [0, 360)] at the start: ``"decreasing"``, ``"increasing"`` or None (at rest, or within the
    hysteresis ``margin`` [deg] of 0 or 180: ``EncodingOptions.hysteresis``).

    The rule is the ``start-gravity-*`` events' preconditions read as VAL reads them (slack
    ``VAL_SLACK``): a link that VAL would see start falling starts with its flag set.
    """
    m = margin
    if m - VAL_SLACK < gamma < 180 - m + VAL_SLACK:
        return "decreasing"
    if gamma > 180 + m - VAL_SLACK:
        return "increasing"
    return None
