"""Clearance of Baxter's arms: signed distances between each arm's collision geoms and the
obstacles (torso and head, the other arm, the pedestal, table, fixture and the object's links).

Used to choose grasps (:mod:`artiplan.world.grasping`): each candidate IK solution, the pair of
arms at their grasps and the rotating arm at its turned poses are checked here
(``mj_geomDistance`` on robosuite's primitive collision shapes) and penalised when closer than a
margin; :func:`repulsion` pushes the grasp IK away from obstacles. The grasping gripper is
allowed to touch the link it holds.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mujoco
import numpy as np

#: Distances beyond this [m] are not computed exactly (GJK stops early): only near pairs matter.
DIST_MAX = 0.2


@dataclass(frozen=True)
class ArmGeoms:
    """Geom ids (and names, for reports) of one arm and of what it must not touch.

    Attributes:
        arm: The arm's collision geoms (shoulder to fingertips).
        gripper: The subset on the gripper (may touch the link it holds).
        shoulder: The subset mounted on the torso (shoulder, e0 housing): not checked against
            it.
        torso: Torso and head collision geoms.
        other: The other arm's collision geoms.
        scene: Pedestal, table and fixture.
        links: Link name -> the link's capsule geom.
    """

    arm: tuple[int, ...]
    gripper: tuple[int, ...]
    shoulder: tuple[int, ...]
    torso: tuple[int, ...]
    other: tuple[int, ...]
    scene: tuple[int, ...]
    links: dict[str, int]
    #: (held, flags) -> the arrays :func:`_pairs` filters (filled on first use).
    cache: dict[tuple[str | None, bool, bool, bool], tuple[np.ndarray, np.ndarray, np.ndarray]] \
        = field(default_factory=dict, init=False, compare=False, repr=False)


def arm_geoms(
    model: mujoco.MjModel, hand: str, links: list[str], prefix: str = "baxter_"
) -> ArmGeoms:
    """Classify the model's geoms for ``hand`` (``left``/``right``). Robot collision geoms are
    those :func:`artiplan.world.baxter_model.attach_baxter` moved to group 3 (robosuite's
    group 0)."""
    other = "right" if hand == "left" else "left"
    arm: list[int] = []
    gripper: list[int] = []
    shoulder: list[int] = []
    torso: list[int] = []
    other_arm: list[int] = []
    for g in range(model.ngeom):
        body = model.body(int(model.geom_bodyid[g])).name
        if not body.startswith(prefix) or int(model.geom_group[g]) != 3:
            continue
        if body.startswith(f"{prefix}{hand}_"):
            arm.append(g)
            if "gripper" in body:
                gripper.append(g)
            # The shoulder and the elbow housing next to it (e0) sit against the torso; the
            # torso is a mesh, i.e. its convex hull for distances, which fills the space
            # around the shoulder mount (e0's housing "penetrates" it by 1-2 cm at ordinary
            # poses): never check those against the torso (the upper arm's own geom is).
            if "shoulder" in body or model.geom(g).name.endswith("_e0_collision"):
                shoulder.append(g)
        elif body.startswith(f"{prefix}{other}_"):
            other_arm.append(g)
        elif "torso" in body or "head" in body:
            torso.append(g)
    scene = []
    for name in ("baxter_pedestal", "table", "fixture_block", "fixture_arm"):
        gid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, name)
        if gid >= 0:
            scene.append(gid)
    link_ids = {link: model.geom(f"{link}_geom").id for link in links}
    return ArmGeoms(
        tuple(arm),
        tuple(gripper),
        tuple(shoulder),
        tuple(torso),
        tuple(other_arm),
        tuple(scene),
        link_ids,
    )


def _pairs(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    geoms: ArmGeoms,
    held: str | None,
    with_links: bool,
    margin: float,
    with_other: bool = True,
    with_body: bool = True,
) -> list[tuple[int, int]]:
    """(arm geom, obstacle geom) pairs to check whose bounding spheres come within
    ``margin`` [m] (a vectorised pre-filter: most pairs are far apart), in the order arm geom,
    then torso, other arm, scene, links. ``with_body``: torso and scene; ``with_other``: the
    other arm; ``with_links``: the object's links. The gripper may touch ``held``; the
    shoulder is not checked against the torso."""
    arm, obstacles, allowed = _candidates(geoms, held, with_links, with_other, with_body)
    if obstacles.size == 0:
        return []
    # One (arm x obstacle) matrix instead of a loop over the arm's geoms: this runs inside
    # every grasp IK iteration (repulsion), where the loop's numpy overhead dominated.
    pos = data.geom_xpos
    gap = np.linalg.norm(pos[obstacles][None, :, :] - pos[arm][:, None, :], axis=2)
    gap -= model.geom_rbound[obstacles][None, :] + model.geom_rbound[arm][:, None]
    rows, cols = np.nonzero((gap < margin) & allowed)
    return list(zip(arm[rows].tolist(), obstacles[cols].tolist(), strict=True))


def _candidates(
    geoms: ArmGeoms, held: str | None, with_links: bool, with_other: bool, with_body: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The arm's geoms, the obstacles and which (arm, obstacle) pairs may be checked at all
    (cached per ``geoms`` and flags: they do not change during a run)."""
    key = (held, with_links, with_other, with_body)
    cache = geoms.cache
    if key not in cache:
        torso = geoms.torso if with_body else ()
        obstacles = np.array([*torso, *(geoms.other if with_other else ()),
                              *(geoms.scene if with_body else ()),
                              *(geoms.links.values() if with_links else ())], dtype=int)
        arm = np.array(geoms.arm, dtype=int)
        allowed = np.ones((arm.size, obstacles.size), dtype=bool)
        shoulder = np.isin(arm, geoms.shoulder)
        allowed[np.ix_(shoulder, np.arange(len(torso)))] = False
        held_id = geoms.links.get(held, -1) if held is not None else -1
        gripper = np.isin(arm, geoms.gripper)
        allowed[np.ix_(gripper, obstacles == held_id)] = False
        cache[key] = (arm, obstacles, allowed)
    return cache[key]


def clearance(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    geoms: ArmGeoms,
    held: str | None = None,
    with_links: bool = True,
    with_other: bool = True,
    with_body: bool = True,
) -> tuple[float, str]:
    """Smallest signed distance [m] (negative: penetration) from the arm to any obstacle in
    ``data``'s current kinematics (call ``mj_kinematics`` first), and the closest pair's names.
    The gripper may touch ``held`` (the link it grasps); distances above :data:`DIST_MAX` are
    reported as DIST_MAX. The flags choose the obstacles: the object's links, the other arm,
    the torso and scene (pedestal, table, fixture)."""
    best, pair = DIST_MAX, ""
    for a, b in _pairs(model, data, geoms, held, with_links, DIST_MAX, with_other, with_body):
        dist = mujoco.mj_geomDistance(model, data, a, b, DIST_MAX, None)
        if dist < best:
            best, pair = dist, f"{model.geom(a).name}~{model.geom(b).name}"
    return float(best), pair


def arm_contacts(model: mujoco.MjModel, data: mujoco.MjData, geoms: ArmGeoms) -> int:
    """Number of (arm geom, torso/other-arm/scene geom) pairs in penetration now."""
    pairs = _pairs(model, data, geoms, None, False, 0.01)
    return sum(mujoco.mj_geomDistance(model, data, a, b, 0.01, None) < 0.0 for a, b in pairs)


def repulsion(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    geoms: ArmGeoms,
    dofs: np.ndarray,
    held: str | None = None,
    margin: float = 0.05,
    with_other: bool = True,
) -> np.ndarray:
    """Joint-space direction (over ``dofs``) pushing the arm's geoms closer than ``margin`` [m]
    away from their obstacles: sum of J_p^T n (margin - distance), J_p the translational
    Jacobian of the arm's closest point, n the unit vector from the obstacle's closest point
    to the arm geom's centre (defined in penetration too). Zero when everything is clear.
    ``with_other`` False: ignore the other arm (whose final place the caller does not know)."""
    dq = np.zeros(len(dofs))
    fromto = np.zeros(6)
    jacp = np.zeros((3, model.nv))
    for a, b in _pairs(model, data, geoms, held, True, margin, with_other):
        dist = mujoco.mj_geomDistance(model, data, a, b, margin, fromto)
        if dist >= margin:
            continue
        n = data.geom_xpos[a] - fromto[3:6]
        norm = float(np.linalg.norm(n))
        if norm < 1e-9:
            continue
        mujoco.mj_jac(model, data, jacp, None, fromto[0:3], int(model.geom_bodyid[a]))
        dq += jacp[:, dofs].T @ (n / norm) * (margin - dist)
    return dq
