"""Goals of the suite: the paper's ``threshold`` goals and the ``window`` goals.

See shared/docs/conventions.md ("Goals of the suite"). Goal links are L3, L5, L7, ... (every
second link from L3; L2 for a 2-link object, which has no L3). Angles in the models live in
[-m, 360), m = ``EncodingOptions.margin`` (see :mod:`artiplan.encoding.domain`).
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Literal

from artiplan.model import PLANES, ArticulatedObject, Configuration
from artiplan.model.angles import in_window_deg, wrap_deg

GoalStyle = Literal["threshold", "window"]
GOAL_STYLES: tuple[str, ...] = ("threshold", "window")
#: The paper's threshold margin [deg]: goals read ``angle > target - 10`` (and one ``<``).
THRESHOLD_MARGIN = 10.0
#: Half-width [deg] of a ``window`` goal: every goal angle within +-5 deg of its target.
WINDOW_HALF_WIDTH = 5.0


def fmt_number(x: float) -> str:
    """A number as PDDL text: integral values without a point, others with <= 6 decimals."""
    x = round(float(x), 6)
    if x.is_integer():
        return str(int(x))
    return f"{x:.6f}".rstrip("0").rstrip(".")


@dataclass(frozen=True)
class AngleBound:
    """One comparison ``(op (angle link plane) value)``, as the paper's goals are written.

    Attributes:
        link: Link name (``L3``).
        plane: Plane name.
        op: ``>`` or ``<``.
        value: Bound [deg], compared with the model's angle as is (no wrap-around).
    """

    link: str
    plane: str
    op: Literal[">", "<"]
    value: float

    def pddl(self) -> str:
        return f"({self.op} (angle {self.link} {self.plane}) {fmt_number(self.value)})"

    def pddl_parts(self) -> tuple[str, ...]:
        return (self.pddl(),)

    def holds(self, angle: float) -> bool:
        """Whether the model angle [deg] satisfies the bound."""
        return angle > self.value if self.op == ">" else angle < self.value


@dataclass(frozen=True)
class AngleWindow:
    """``angle`` within ``half_width`` of ``centre`` [deg], across the 0/360 wrap.

    Attributes:
        link: Link name.
        plane: Plane name.
        centre: Target angle [deg].
        half_width: Accepted deviation either side [deg].
    """

    link: str
    plane: str
    centre: float
    half_width: float = WINDOW_HALF_WIDTH

    def pddl_parts(self) -> tuple[str, ...]:
        """``(>= a lo)`` and ``(<= a hi)``, or one ``or`` of the two pieces when it wraps."""
        a = f"(angle {self.link} {self.plane})"
        lo = self.centre - self.half_width
        hi = self.centre + self.half_width
        if lo < 0.0:
            return (f"(or (>= {a} {fmt_number(lo + 360.0)}) (<= {a} {fmt_number(hi)}))",)
        if hi >= 360.0:
            return (f"(or (>= {a} {fmt_number(lo)}) (<= {a} {fmt_number(hi - 360.0)}))",)
        return (f"(>= {a} {fmt_number(lo)})", f"(<= {a} {fmt_number(hi)})")

    def pddl(self) -> str:
        """The window as one condition."""
        parts = self.pddl_parts()
        return parts[0] if len(parts) == 1 else f"(and {' '.join(parts)})"

    def holds(self, angle: float) -> bool:
        """Whether ``angle`` [deg] is inside the window (any representation of it)."""
        return in_window_deg(wrap_deg(angle), self.centre, self.half_width + 1e-9)


GoalCondition = AngleBound | AngleWindow


@dataclass(frozen=True)
class GoalSpec:
    """A conjunction of angle conditions.

    Attributes:
        style: ``threshold`` or ``window``.
        conditions: The conjuncts, in the order they are written.
    """

    style: str
    conditions: tuple[GoalCondition, ...]

    @property
    def links(self) -> tuple[str, ...]:
        """Goal links, in order of first mention."""
        return tuple(dict.fromkeys(c.link for c in self.conditions))

    def pddl(self, indent: str = "    ") -> str:
        """The ``(:goal ...)`` body: ``(and ...)`` with one condition a line."""
        body = "\n".join(indent + part for c in self.conditions for part in c.pddl_parts())
        return f"(and\n{body})"

    def holds(self, obj: ArticulatedObject, conf: Configuration) -> bool:
        """Whether ``conf`` (angles as the model holds them) satisfies every condition."""
        return all(c.holds(conf.angle(obj.index(c.link), c.plane)) for c in self.conditions)


def goal_links(obj: ArticulatedObject) -> tuple[str, ...]:
    """L3, L5, L7, ... (L2 alone for a 2-link object)."""
    if obj.n_links < 3:
        return ("L2",)
    return tuple(obj.links[i] for i in range(2, obj.n_links, 2))


def make_goal(
    obj: ArticulatedObject,
    target: Configuration,
    style: str = "threshold",
    seed: int = 0,
    planes: tuple[str, ...] = PLANES,
    tolerance: float | None = None,
) -> GoalSpec:
    """The goal for reaching ``target``.

    Args:
        obj: The object.
        target: Target configuration [deg].
        style: ``threshold`` (the paper's: ``angle > target - 10`` on every goal link and plane,
            plus one ``angle < target + 10`` on a link and plane chosen by ``seed``) or
            ``window`` (every goal angle within +-tolerance of its target, across the wrap).
        seed: Chooses the threshold style's upper bound (``random.Random(seed)``).
        planes: Planes the goal names.
        tolerance: Margin [deg]; default 10 (threshold) or 5 (window).

    Returns:
        The goal as a :class:`GoalSpec`.
    """
    if style not in GOAL_STYLES:
        raise ValueError(f"unknown goal style {style!r}; valid styles: {', '.join(GOAL_STYLES)}")
    if target.n_links != obj.n_links:
        raise ValueError(f"object has {obj.n_links} links, target {target.n_links}")
    links = goal_links(obj)
    angles = [(lk, p, wrap_deg(target.angle(obj.index(lk), p))) for lk in links for p in planes]
    conditions: list[GoalCondition] = []
    if style == "window":
        hw = WINDOW_HALF_WIDTH if tolerance is None else tolerance
        conditions = [AngleWindow(lk, p, v, hw) for lk, p, v in angles]
        return GoalSpec("window", tuple(conditions))
    margin = THRESHOLD_MARGIN if tolerance is None else tolerance
    conditions = [AngleBound(lk, p, ">", v - margin) for lk, p, v in angles]
    lk, p, v = random.Random(seed).choice(angles)
    conditions.append(AngleBound(lk, p, "<", v + margin))
    return GoalSpec("threshold", tuple(conditions))
