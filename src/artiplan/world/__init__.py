"""The simulated world: MuJoCo physics of the articulated object, hands, perception, ontology.

Set ``MUJOCO_GL=egl`` (or ``osmesa``) before importing this package if you render images.
"""

from __future__ import annotations

from artiplan.errors import UsageError
from artiplan.model import ArticulatedObject, Configuration
from artiplan.world.hands import Hands, VirtualHands
from artiplan.world.perception import Percept, PerceptionConfig
from artiplan.world.presets import PRESETS, JointPhysics, preset
from artiplan.world.scene import IMPACT_STOP_M, World, WorldConfig
from artiplan.world.servo import ServoGains

__all__ = [
    "PRESETS",
    "Hands",
    "JointPhysics",
    "Percept",
    "PerceptionConfig",
    "ServoGains",
    "VirtualHands",
    "World",
    "WorldConfig",
    "make_world",
    "preset",
]


def make_world(
    obj: ArticulatedObject,
    conf: Configuration | None = None,
    *,
    preset: str = "stiff",
    hands: str = "virtual",
    seed: int = 0,
    perception: PerceptionConfig | None = None,
    approach_s: float = 0.0,
    avoid_collisions: bool = True,
    impact_stop_m: float | None = IMPACT_STOP_M,
    strain_stop: bool = False,
) -> World:
    """A world with named settings: ``preset`` stiff|loose, ``hands`` virtual|baxter
    (``approach_s`` > 0: Baxter's arms move to each grasp in simulated time, along planned
    motions taking at least that many seconds; ``avoid_collisions``: Baxter's grasps and
    motions collision-free; ``impact_stop_m``: see :class:`WorldConfig`, None: off;
    ``strain_stop``: see :class:`WorldConfig`). Baxter serves
    objects of up to :data:`artiplan.world.baxter_model.BAXTER_MAX_LINKS` links: a longer one raises
    :class:`artiplan.errors.UsageError`."""
    from artiplan.world.presets import preset as get_preset

    config = WorldConfig(
        physics=get_preset(preset), perception=perception or PerceptionConfig(), seed=seed
    )
    if hands == "virtual":
        return World(obj, conf, config, VirtualHands())
    if hands == "baxter":
        from artiplan.world.baxter import BAXTER_MAX_LINKS, BaxterHands, baxter_layout

        if obj.n_links > BAXTER_MAX_LINKS:
            raise UsageError(
                f"Baxter serves objects of up to {BAXTER_MAX_LINKS} links (a longer chain "
                f"hangs below its reach); this one has {obj.n_links}: use virtual hands")

        return World(
            obj,
            conf,
            WorldConfig(config.physics, config.perception, seed, layout=baxter_layout(obj),
                        impact_stop_m=impact_stop_m, strain_stop=strain_stop),
            BaxterHands(approach_s=approach_s, avoid_collisions=avoid_collisions),
        )
    raise ValueError(f"unknown hands {hands!r}; valid: virtual, baxter")
