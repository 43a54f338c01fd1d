"""MJCF of the scene: floor, table, fixture, the articulated object, cameras, virtual hands.

Link body ``Lk`` has its frame at the link's base-end joint and its capsule along local -z, so
the identity orientation hangs straight down. L1 has no joint: it is clamped to the fixture.
Every other link hangs from its parent by a ball joint ``Jk`` (at qpos0 the configuration the
scene was built with). Units: metres, kilograms, seconds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from artiplan.model import ArticulatedObject, Configuration
from artiplan.world.presets import JointPhysics
from artiplan.world.rotations import Vec, link_quat, quat_conj, quat_mul

#: Link colours (RGB), one per link, cycled: matplotlib's tab10.
LINK_COLOURS: tuple[tuple[float, float, float], ...] = (
    (0.12, 0.47, 0.71), (1.00, 0.50, 0.05), (0.17, 0.63, 0.17), (0.84, 0.15, 0.16),
    (0.58, 0.40, 0.74), (0.55, 0.34, 0.29), (0.89, 0.47, 0.76), (0.50, 0.50, 0.50),
    (0.74, 0.74, 0.13), (0.09, 0.75, 0.81),
)  # fmt: skip

#: Contact bits: links collide with the table and floor, not with each other or the hands.
LINK_CONTYPE, LINK_CONAFFINITY = 2, 0
ENV_CONTYPE, ENV_CONAFFINITY = 1, 2

HAND_NAMES = ("left", "right")


@dataclass(frozen=True)
class SceneLayout:
    """Where things are in the world frame [m].

    Attributes:
        anchor: World position of the object's frame origin; L1's base end is at
            ``anchor + obj.base_position``.
        table_top: Height of the table top (it sits under the hanging chain).
        with_table: Draw and collide with the table.
        virtual_hands: Add two mocap hands and their (inactive) welds to every link.
        weld_solref: Weld constraint time constant and damping ratio (grasp stiffness).
        fixture_arm: The fixture's arm, from the clamp to its post, relative to the clamp [m].
    """

    anchor: tuple[float, float, float]
    table_top: float
    with_table: bool = True
    virtual_hands: bool = True
    weld_solref: tuple[float, float] = (0.005, 1.0)
    fixture_arm: tuple[float, float, float] = (-0.35, 0.0, 0.0)


def default_layout(obj: ArticulatedObject, virtual_hands: bool = True) -> SceneLayout:
    """A layout where the chain hangs freely: the base is one chain length above the table."""
    reach = obj.n_links * obj.link_length
    return SceneLayout(anchor=(0.0, 0.0, reach + 0.25), table_top=0.15, virtual_hands=virtual_hands)


def relative_quats(conf: Configuration) -> list[Vec]:
    """Per link: its orientation relative to its parent (L1: relative to the world)."""
    absolute = [link_quat(t, g) for t, g in zip(conf.theta, conf.gamma, strict=True)]
    rel = [absolute[0]]
    rel += [quat_mul(quat_conj(absolute[i - 1]), absolute[i]) for i in range(1, len(absolute))]
    return rel


def _f(v: object) -> str:
    return " ".join(f"{x:.9g}" for x in np.ravel(np.asarray(v, dtype=float)))


def _link_xml(obj: ArticulatedObject, conf: Configuration, phys: JointPhysics, top: Vec) -> str:
    """Nested bodies L1 > L2 > ... > Ln, L1's base end at ``top`` (world)."""
    rels = relative_quats(conf)
    radius = obj.thickness / 2.0
    length = obj.link_length
    opened: list[str] = []
    for i in range(obj.n_links):
        name = f"L{i + 1}"
        pos = top if i == 0 else np.array([0.0, 0.0, -length])
        rgb = LINK_COLOURS[i % len(LINK_COLOURS)]
        joint = ""
        if i > 0:
            carried = obj.n_links - i
            joint = (
                f'<joint name="J{i + 1}" type="ball" damping="{phys.joint_damping(carried):.9g}" '
                f'frictionloss="{phys.frictionloss:.9g}" armature="{phys.armature:.9g}"/>'
            )
        opened.append(
            f'<body name="{name}" pos="{_f(pos)}" quat="{_f(rels[i])}">{joint}'
            f'<geom name="{name}_geom" type="capsule" fromto="0 0 0 0 0 {-length:.9g}" '
            f'size="{radius:.9g}" mass="{obj.mass:.9g}" rgba="{_f(rgb)} 1" '
            f'contype="{LINK_CONTYPE}" conaffinity="{LINK_CONAFFINITY}"/>'
            f'<site name="{name}_centre" pos="0 0 {-length / 2:.9g}" size="0.004"/>'
        )
    return "".join(opened) + "</body>" * obj.n_links


def _hands_xml(obj: ArticulatedObject, layout: SceneLayout) -> tuple[str, str]:
    """Two mocap hands (worldbody part) and a weld per hand and link (equality part)."""
    bodies, welds = [], []
    half = obj.link_length / 2.0
    solref = _f(layout.weld_solref)
    for k, hand in enumerate(HAND_NAMES):
        park = np.asarray(layout.anchor) + np.array([0.4, (-1) ** k * 0.3, 0.2])
        rgba = "0.95 0.8 0.6 0.55" if k == 0 else "0.6 0.8 0.95 0.55"
        bodies.append(
            f'<body name="hand_{hand}" mocap="true" pos="{_f(park)}">'
            f'<geom name="hand_{hand}_geom" type="box" size="0.03 0.03 0.035" '
            f'pos="0 0 {-half:.9g}" rgba="{rgba}" contype="0" conaffinity="0"/></body>'
        )
        welds += [
            f'<weld name="weld_{hand}_{link}" body1="hand_{hand}" body2="{link}" '
            f'active="false" solref="{solref}"/>'
            for link in obj.links
        ]
    return "".join(bodies), "".join(welds)


def _cameras_xml(obj: ArticulatedObject, layout: SceneLayout) -> str:
    """An overhead camera looking straight down and a side camera looking along +y."""
    a = np.asarray(layout.anchor) + np.asarray(obj.base_position)
    extent = obj.n_links * obj.link_length + 0.12
    dist = extent / np.tan(np.radians(22.5))
    over = a + np.array([0.0, 0.0, dist])
    mid_z = a[2] - 0.25 * extent
    side = np.array([a[0], a[1] - 1.05 * dist, mid_z])
    persp = a + np.array([0.9 * dist, -0.9 * dist, 0.45 * dist])
    return (
        f'<camera name="overhead" pos="{_f(over)}" xyaxes="1 0 0 0 1 0" fovy="45"/>'
        f'<camera name="side" pos="{_f(side)}" xyaxes="1 0 0 0 0 1" fovy="45"/>'
        f'<camera name="perspective" pos="{_f(persp)}" mode="targetbody" target="L1" fovy="45"/>'
    )


def scene_xml(
    obj: ArticulatedObject, conf: Configuration, phys: JointPhysics, layout: SceneLayout
) -> str:
    """The whole scene as an MJCF string (built at ``conf``)."""
    if conf.n_links != obj.n_links:
        raise ValueError(f"object has {obj.n_links} links, configuration {conf.n_links}")
    a = np.asarray(layout.anchor)
    top = a + np.asarray(obj.base_position)
    hands, welds = _hands_xml(obj, layout) if layout.virtual_hands else ("", "")
    table = ""
    if layout.with_table:
        t = layout.table_top
        table = (
            f'<geom name="table" type="box" pos="{_f([a[0], a[1], t - 0.02])}" '
            f'size="0.45 0.45 0.02" rgba="0.55 0.42 0.3 1" contype="{ENV_CONTYPE}" '
            f'conaffinity="{ENV_CONAFFINITY}"/>'
        )
    arm = np.asarray(layout.fixture_arm) + np.array([0.0, 0.0, 0.03])
    post = (
        f'<body name="fixture" pos="{_f(top)}">'
        f'<geom name="fixture_block" type="box" size="0.03 0.03 0.03" pos="0 0 0.03" '
        f'rgba="0.25 0.25 0.28 1" contype="0" conaffinity="0"/>'
        f'<geom name="fixture_arm" type="capsule" fromto="0 0 0.03 {_f(arm)}" size="0.012" '
        f'rgba="0.25 0.25 0.28 1" contype="0" conaffinity="0"/></body>'
    )
    return f"""<mujoco model="artiplan_world">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="{phys.timestep:.9g}" integrator="implicitfast" gravity="0 0 -9.81"/>
  <visual><headlight ambient="0.35 0.35 0.35" diffuse="0.5 0.5 0.5" specular="0.1 0.1 0.1"/>
    <quality shadowsize="0"/><global offwidth="1280" offheight="960"/></visual>
  <asset>
    <texture name="grid" type="2d" builtin="checker" rgb1="0.82 0.84 0.86"
      rgb2="0.72 0.74 0.76" width="256" height="256"/>
    <texture name="sky" type="skybox" builtin="gradient" rgb1="0.55 0.68 0.85"
      rgb2="0.95 0.96 0.98" width="256" height="256"/>
    <material name="grid" texture="grid" texrepeat="8 8" reflectance="0"/>
  </asset>
  <worldbody>
    <light name="sun" pos="0 0 6" dir="0.2 0.3 -1" directional="true" castshadow="false"
      diffuse="0.6 0.6 0.6"/>
    <geom name="floor" type="plane" size="4 4 0.1" material="grid"
      contype="{ENV_CONTYPE}" conaffinity="{ENV_CONAFFINITY}"/>
    {table}{post}
    {_link_xml(obj, conf, phys, top)}
    {hands}
    {_cameras_xml(obj, layout)}
  </worldbody>
  <equality>{welds}</equality>
</mujoco>
"""
