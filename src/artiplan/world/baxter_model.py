"""Baxter's model in the scene: robosuite's MJCF found at run time (never imported, never
copied), its grippers, the pedestal, one inactive weld per (hand, link), and the contact bits
that make the arms collide with the torso, each other, the scene and the object
(:mod:`artiplan.world.contacts`)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import mujoco

from artiplan.model import ArticulatedObject
from artiplan.world.contacts import LINK, SCENE, TORSO, arm_bits, link_bit
from artiplan.world.mjcf import SceneLayout

#: Where Baxter's base sits in the world [m] (on a pedestal, facing +x).
BAXTER_BASE = (0.0, 0.0, 0.9)
PREFIX = "baxter_"
#: The longest chain Baxter serves: longer ones hang below its reach (use virtual hands).
BAXTER_MAX_LINKS = 6


def baxter_xml_path() -> Path:
    """robosuite's ``robots/baxter/robot.xml`` (raises FileNotFoundError when absent)."""
    spec = importlib.util.find_spec("robosuite")
    if spec is None or not spec.submodule_search_locations:
        raise FileNotFoundError("the robosuite wheel is not installed (pip install --no-deps)")
    root = Path(next(iter(spec.submodule_search_locations)))
    path = root / "models" / "assets" / "robots" / "baxter" / "robot.xml"
    if not path.exists():
        raise FileNotFoundError(f"no Baxter model at {path}")
    return path


def baxter_layout(obj: ArticulatedObject) -> SceneLayout:
    """The object in front of Baxter, its fixture a little above shoulder height (higher for
    chains longer than 6 links, so they hang free of the floor; Baxter reaches only the upper
    links of those: use virtual hands)."""
    height = max(1.12, obj.n_links * obj.link_length + 0.15)
    return SceneLayout(
        anchor=(0.62, 0.0, height), table_top=0.3, virtual_hands=False, fixture_arm=(0.4, 0.0, 0.0)
    )


def attach_baxter(spec: mujoco.MjSpec, obj: ArticulatedObject) -> None:
    """Attach Baxter to ``spec`` and add an inactive weld per (hand, link)."""
    robot = mujoco.MjSpec.from_file(str(baxter_xml_path()))
    gripper_xml = baxter_xml_path().parents[2] / "grippers" / "rethink_gripper.xml"
    if gripper_xml.exists():  # Rethink's electric grippers on both wrists (visual fingers)
        for hand in ("left", "right"):
            gripper = mujoco.MjSpec.from_file(str(gripper_xml))
            for site in gripper.sites:  # robosuite's visual aids (long grip-axis cylinders)
                site.group = 4
            robot.body(f"{hand}_hand").add_frame().attach_body(
                gripper.worldbody.first_body(), f"{hand}_gripper_", ""
            )
    for b in robot.bodies:
        for g in b.geoms:
            g.contype, g.conaffinity = _bits(b.name, g.name, g.group, obj.n_links)
            if g.group == 0:  # robosuite's collision shapes: keep them out of the images
                g.group = 3
    for b in robot.bodies:
        # Baxter's shoulder springs and controller carry the arm's own weight: model that as
        # MuJoCo's passive gravity compensation, so the motors' limits are left for motion
        # and the object (without it s1 needs ~90 of its 100 N m just to hold the arm out).
        b.gravcomp = 1.0
    spec.worldbody.add_geom(
        name="baxter_pedestal",
        type=mujoco.mjtGeom.mjGEOM_CYLINDER,
        size=[0.22, BAXTER_BASE[2] / 2 - 0.05, 0],
        pos=[BAXTER_BASE[0] - 0.05, BAXTER_BASE[1], BAXTER_BASE[2] / 2 - 0.05],
        rgba=[0.2, 0.2, 0.22, 1.0],
        contype=SCENE,
        conaffinity=0,
    )
    for name in ("fixture_block", "fixture_arm"):
        spec.geom(name).contype = SCENE
    for i, link in enumerate(obj.links, start=1):
        spec.geom(f"{link}_geom").contype = LINK | link_bit(i)
    frame = spec.worldbody.add_frame(pos=list(BAXTER_BASE))
    frame.attach_body(robot.worldbody.first_body(), PREFIX, "")
    for hand in ("left", "right"):
        for link in obj.links:
            eq = spec.add_equality()
            eq.name = f"weld_{hand}_{link}"
            eq.type = mujoco.mjtEq.mjEQ_WELD
            eq.objtype = mujoco.mjtObj.mjOBJ_BODY
            eq.name1, eq.name2 = f"{PREFIX}{hand}_hand", link
            eq.active = False
            eq.solref = [0.005, 1.0]


def _bits(body: str, geom: str, group: int, n_links: int) -> tuple[int, int]:
    """(contype, conaffinity) of a robot geom by its (unprefixed) body and name: collision
    shapes (group 0) of the arms, torso and head collide; visual meshes do not."""
    if group != 0:
        return 0, 0
    if "torso" in body or "head" in body:
        return TORSO, 0
    hand = "left" if body.startswith("left_") else "right"
    if "gripper" in body:
        return arm_bits(hand, "gripper", n_links)
    # The shoulder and the e0 housing next to it sit inside the torso mesh's convex hull.
    shoulder = "shoulder" in body or geom.endswith("_e0_collision")
    return arm_bits(hand, "shoulder" if shoulder else "arm", n_links)
