"""The simulated world: MuJoCo physics of the articulated object, hands, perception, ontology.

Set ``MUJOCO_GL=egl`` (or ``osmesa``) before importing this package if you render images.
"""

from __future__ import annotations

from artiplan.model import ArticulatedObject, Configuration
from artiplan.world.hands import Hands, VirtualHands
from artiplan.world.perception import Percept, PerceptionConfig
from artiplan.world.presets import PRESETS, JointPhysics, preset
from artiplan.world.scene import World, WorldConfig
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
) -> World:
    """A world with named settings: ``preset`` stiff|loose, ``hands`` virtual|baxter
    (``approach_s`` > 0: Baxter's arms move to each grasp in that many simulated seconds;
    ``avoid_collisions``: Baxter's grasps chosen and solved clear of the torso, arms, table)."""
    from artiplan.world.presets import preset as get_preset

    config = WorldConfig(
        physics=get_preset(preset), perception=perception or PerceptionConfig(), seed=seed
    )
    if hands == "virtual":
        return World(obj, conf, config, VirtualHands())
    if hands == "baxter":
        from artiplan.world.baxter import BaxterHands, baxter_layout

        return World(
            obj,
            conf,
            WorldConfig(config.physics, config.perception, seed, layout=baxter_layout(obj)),
            BaxterHands(approach_s=approach_s, avoid_collisions=avoid_collisions),
        )
    raise ValueError(f"unknown hands {hands!r}; valid: virtual, baxter")
