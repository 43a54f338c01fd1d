"""Physics parameters of the object's joints, with the two presets of issue 6.

``stiff`` is overdamped: a released link falls at a nearly constant speed (the UCM regime);
``loose`` is lightly damped: a released link accelerates first and swings (the UACM regime).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType


@dataclass(frozen=True)
class JointPhysics:
    """Ball-joint parameters of the articulated object.

    Attributes:
        damping: Viscous damping of the joint between L1 and L2's subchain when that subchain is
            one link [N m s/rad]. With ``scale_by_load`` joint j gets ``damping * c**2`` where c
            is the number of links tip-ward of it (itself included): a straight subchain's gravity
            torque grows as c**2, so every joint falls at a comparable speed.
        frictionloss: Coulomb friction of every joint [N m].
        armature: Rotor inertia added to every joint [kg m^2] (numerical stability).
        scale_by_load: Scale damping with the load a joint carries (see above).
        timestep: Physics step [s] (integrator ``implicitfast``).
    """

    damping: float = 3.0
    frictionloss: float = 0.0
    armature: float = 1e-4
    scale_by_load: bool = True
    timestep: float = 0.002

    def __post_init__(self) -> None:
        if self.damping < 0 or self.frictionloss < 0 or self.armature < 0:
            raise ValueError("damping, frictionloss and armature must be >= 0")
        if self.timestep <= 0:
            raise ValueError("timestep must be positive")

    def joint_damping(self, carried: int) -> float:
        """Damping [N m s/rad] of a joint whose subchain has ``carried`` links."""
        return self.damping * (carried**2 if self.scale_by_load else 1)


#: A 0.05 kg, 0.15 m link held horizontal feels 0.037 N m; 3.0 N m s/rad -> ~0.7 deg/s.
#: ``stiff`` armature: 3e-3 kg m^2 (8x a link's own 3.75e-4 about its joint). With 1e-4 a
#: joint between two links held by Baxter's grippers chattered at up to 6500 rad/s^2, and in
#: 6-link task 11 (every run of sessions 20-25) MuJoCo diverged within 12 ms of the two
#: grippers touching (4 mm); from the same state with 3e-3: 330 rad/s^2 and no divergence.
#: The overdamped fall is unchanged (time constant 1 ms; calibrated speed-g 0.9476 against
#: 0.9478 on 4 links). ``loose`` keeps 1e-4: its swing depends on the link's inertia.
PRESETS = MappingProxyType(
    {
        "stiff": JointPhysics(damping=3.0, frictionloss=0.0, armature=3e-3),
        "loose": JointPhysics(damping=0.002, frictionloss=0.0, armature=1e-4),
    }
)


def preset(name: str) -> JointPhysics:
    """The named preset (``stiff`` or ``loose``)."""
    try:
        return PRESETS[name]
    except KeyError:
        raise ValueError(f"unknown preset {name!r}; valid presets: {', '.join(PRESETS)}") from None
