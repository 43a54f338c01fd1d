"""Encoding options: which gravity model, its speeds, the planes (a frozen config dataclass)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from artiplan.model import HORIZONTAL_PLANE, PLANES, VERTICAL_PLANE
from artiplan.tolerances import VAL_EVENT_WINDOW

#: Smallest wrap-around and hysteresis margin [deg]: 100 times VAL's comparison slack.
MIN_MARGIN = 0.01
#: Link speed [deg/s] the gravity flags' hysteresis is sized for. A link carried by
#: falling links base-ward of it turns at the sum of their speeds, far above the robot's: up to
#: 80 deg/s measured on 30-link UACM chains (benchmarks/results/semantics.md).
GRAVITY_LINK_SPEED = 50.0

Model = Literal["ng", "ucm", "uacm"]
MODELS: tuple[str, ...] = ("ng", "ucm", "uacm")
Carry = Literal["rigid", "projected"]
CARRIES: tuple[str, ...] = ("rigid", "projected")
Fall = Literal["uniform", "torque"]
FALLS: tuple[str, ...] = ("uniform", "torque")


@dataclass(frozen=True)
class EncodingOptions:
    """How to encode an articulated object in PDDL+.

    Attributes:
        model: ``"ng"`` (no gravity), ``"ucm"`` (uniform circular motion) or ``"uacm"``
            (uniformly accelerated circular motion).
        speed_i: Robot rotation speed when increasing an angle [deg/s].
        speed_d: Robot rotation speed when decreasing an angle [deg/s].
        speed_g: UCM only: angular speed of a link under gravity [deg/s].
        acceleration: UACM only: angular acceleration of a link under gravity [deg/s^2].
        planes: Plane names, one angle per link on each (default ``xy-axes``, ``z-axis``).
        gravity_plane: The plane on which gravity acts (must be one of ``planes``).
        reach_time: Optional time [s] the robot needs between releasing a link and the next
            grasp (``None``: grasps are instantaneous, as in the paper). Gravity keeps acting
            meanwhile. A reach time shorter than 1.5 x VAL's event window (15 ms) is modelled
            as instantaneous: VAL would fire ``hands-ready`` at the release itself, and then
            lose the processes the release starts (benchmarks/results/semantics.md).
        carry: How a vertical-plane rotation (the robot's or gravity's) moves the links it
            carries. ``rigid`` (the paper): every carried link's gamma changes at the rotated
            link's rate. ``projected``: at that rate times ``cos(theta_j - theta_k)``, the
            exact instantaneous rate for a link j carried by a turn of link k about the
            horizontal normal of k's vertical plane (the rigid rule is right only for links in
            that plane; a link across it barely changes gamma). The factors are problem
            constants ``(carry ?k ?j ?p)`` computed from the initial thetas (1 on other planes:
            a turn about the vertical is exact).
        refusals: Add what the closed loop needs to plan around rotations the robot has
            just refused (``(refused-increase ?l1 ?l2 ?p)``, ``(refused-decrease ...)``: no
            such start until a turn of ?l2 or of a link base-ward of it has stopped, which
            makes ``(unlocked ?l2)``). Off by default: the suite's domains do not have it.
        fall: UCM only. ``uniform`` (the paper): every free link falls at ``speed-g``.
            ``torque``: link l falls at ``speed-g`` times ``(fall l)``, a problem constant
            from the initial configuration: its joint's rate in an overdamped chain whose
            joint damping grows with the load, relative to a straight horizontal subchain's
            (:mod:`artiplan.encoding.fall`; links near rest, or folded back over their
            joint, fall much more slowly). For the closed loop, which re-plans from each
            percept; the suite's domains do not have it.
        max_turn_deg: The longest turn [deg] a plan may make in one grasp (None: any): a
            turn is stopped, and a plan ends, before it has gone further. For the closed
            loop: with a reach time the planner preferred one long turn to several short
            ones, up to 3 revolutions of L3 carrying L4-L6 (1109 deg) to line its goal links
            up with their windows, which arms do in many re-grasps and the carried links do
            not follow as modelled; 180 deg reaches any angle the shorter way round.
    """

    model: Model = "ng"
    speed_i: float = 10.0
    speed_d: float = 10.0
    speed_g: float = 0.1
    acceleration: float = 0.1
    planes: tuple[str, ...] = PLANES
    gravity_plane: str = VERTICAL_PLANE
    reach_time: float | None = None
    carry: Carry = "rigid"
    refusals: bool = False
    fall: Fall = "uniform"
    max_turn_deg: float | None = None

    def __post_init__(self) -> None:
        if self.model not in MODELS:
            raise ValueError(f"unknown model {self.model!r}; valid models: {', '.join(MODELS)}")
        for name in ("speed_i", "speed_d", "speed_g", "acceleration"):
            if getattr(self, name) <= 0:
                raise ValueError(f"{name} must be positive, got {getattr(self, name)}")
        if not self.planes or len(set(self.planes)) != len(self.planes):
            raise ValueError(f"planes must be distinct and non-empty, got {self.planes}")
        if self.model != "ng" and self.gravity_plane not in self.planes:
            raise ValueError(
                f"gravity plane {self.gravity_plane!r} is not one of the planes {self.planes}"
            )
        if self.carry not in CARRIES:
            raise ValueError(f"unknown carry {self.carry!r}; valid: {', '.join(CARRIES)}")
        if self.fall not in FALLS:
            raise ValueError(f"unknown fall {self.fall!r}; valid: {', '.join(FALLS)}")
        if self.fall != "uniform" and self.model != "ucm":
            raise ValueError(f"fall={self.fall!r} needs the ucm model, not {self.model!r}")
        if self.reach_time is not None and self.reach_time < 0:
            raise ValueError(f"reach_time must be >= 0, got {self.reach_time}")
        if self.max_turn_deg is not None and self.max_turn_deg <= 0:
            raise ValueError(f"max_turn_deg must be positive, got {self.max_turn_deg}")

    @property
    def has_gravity(self) -> bool:
        """True for UCM and UACM."""
        return self.model != "ng"

    @property
    def has_reach(self) -> bool:
        """True when the domain models the reach time (see ``reach_time``)."""
        return self.reach_time is not None and self.reach_time >= 1.5 * VAL_EVENT_WINDOW

    @property
    def counts_turn(self) -> bool:
        """True when the domain keeps ``(turned)``, the degrees of the turn in progress
        (for ``refusals`` and ``max_turn_deg``)."""
        return self.refusals or self.max_turn_deg is not None

    @property
    def torque_fall(self) -> bool:
        """True when UCM's fall speed is scaled per link (``fall="torque"``)."""
        return self.fall == "torque"

    @property
    def margin(self) -> float:
        """Margin [deg] of the wrap-around: angles live in [-margin, 360).

        A wrap and the event of the same motion before it (0 passed, then -margin) must be
        more than VAL's event window apart in time, or VAL merges them into one happening:
        twice the window at the fastest robot speed, and at least :data:`MIN_MARGIN` (0.2 deg
        at the default 10 deg/s).
        """
        fastest = max(self.speed_i, self.speed_d)
        return max(MIN_MARGIN, round(2.0 * VAL_EVENT_WINDOW * fastest, 6))

    @property
    def hysteresis(self) -> float:
        """Hysteresis [deg] of the gravity flags: a link within it of 0 or 180 does not
        start to fall.

        A stop and the next start of one link's flags (0 passed, then +hysteresis) must be
        more than VAL's event window apart, or VAL fires both at one happening and reports an
        event triggered twice. A link carried by falling links turns at the sum of their
        speeds, far above the robot's: twice the window at :data:`GRAVITY_LINK_SPEED` at least
        (1 deg), and never below :attr:`margin`.
        """
        return max(self.margin, round(2.0 * VAL_EVENT_WINDOW * GRAVITY_LINK_SPEED, 6))

    @property
    def azimuth_plane(self) -> str | None:
        """With the ``projected`` carry: the horizontal plane whose angle a vertical turn also
        changes (None for the rigid carry, or when there is no such plane)."""
        if self.carry != "projected" or self.gravity_plane == HORIZONTAL_PLANE:
            return None
        return HORIZONTAL_PLANE if HORIZONTAL_PLANE in self.planes else None
