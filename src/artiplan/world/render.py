"""Headless camera images of the world: RGB, depth, link segmentation.

MuJoCo picks its OpenGL backend when it is first imported: set ``MUJOCO_GL=egl`` (or
``osmesa``) in the environment before importing :mod:`artiplan.world` (``artiplan world``
does this for you).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import mujoco
import numpy as np

from artiplan.world.mjcf import LINK_COLOURS
from artiplan.world.rotations import Vec

if TYPE_CHECKING:
    from artiplan.world.scene import World

KINDS = ("rgb", "depth", "segmentation")


def render(
    world: World, camera: str, kind: str, width: int, height: int, frame: bool = True
) -> Vec:
    """One image; see :meth:`artiplan.world.scene.World.render`.

    With ``frame`` the named camera (overhead, side, perspective) is first moved so the object,
    as it is now, fills the image (the overhead camera still looks straight down).
    """
    if kind not in KINDS:
        raise ValueError(f"unknown image kind {kind!r}; valid kinds: {', '.join(KINDS)}")
    model = world.model
    if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, camera) < 0:
        names = [model.camera(i).name for i in range(model.ncam)]
        raise ValueError(f"unknown camera {camera!r}; cameras: {', '.join(names)}")
    if frame:
        _frame_camera(world, camera, width / height)
    renderer = world.renderer(width, height)
    renderer.disable_depth_rendering()
    renderer.disable_segmentation_rendering()
    if kind == "depth":
        renderer.enable_depth_rendering()
    elif kind == "segmentation":
        renderer.enable_segmentation_rendering()
    renderer.update_scene(world.data, camera=camera)
    image = renderer.render()
    if kind == "segmentation":
        return _link_labels(world, image)
    return np.asarray(image)


#: Viewing directions (camera -> object) of the framed cameras.
VIEWS = {
    "overhead": np.array([0.0, 0.0, -1.0]),
    "side": np.array([0.0, 1.0, 0.0]),
    "perspective": np.array([-0.62, 0.62, -0.48]),
}


def _frame_camera(world: World, camera: str, aspect: float) -> None:
    """Place ``camera`` so the object's bounding sphere fills the view."""
    if camera not in VIEWS:
        return
    pts = np.vstack([world.data.xpos[world.model.body(link).id] for link in world.obj.links])
    tip = pts[-1] + world.obj.link_length * world.link_directions()[-1]
    pts = np.vstack([pts, tip])
    if camera == "perspective":  # show the robot's hands too, when there is a robot
        names = ("baxter_left_hand", "baxter_right_hand", "baxter_head")
        ids = [mujoco.mj_name2id(world.model, mujoco.mjtObj.mjOBJ_BODY, n) for n in names]
        pts = np.vstack([pts] + [world.data.xpos[i] for i in ids if i >= 0])
    centre = 0.5 * (pts.min(axis=0) + pts.max(axis=0))
    radius = float(np.max(np.linalg.norm(pts - centre, axis=1))) + 0.08
    cam = world.model.camera(camera).id
    half_fov = np.radians(world.model.cam_fovy[cam] / 2.0) * min(1.0, aspect)
    forward = VIEWS[camera] / np.linalg.norm(VIEWS[camera])
    world.model.cam_pos[cam] = centre - forward * radius / np.sin(half_fov)
    right = np.cross(forward, np.array([0.0, 0.0, 1.0]))
    right = right / np.linalg.norm(right) if np.linalg.norm(right) > 1e-9 else np.eye(3)[0]
    up = np.cross(right, forward)
    mat = np.column_stack([right, up, -forward])
    quat = np.empty(4)
    mujoco.mju_mat2Quat(quat, mat.ravel())
    world.model.cam_quat[cam] = quat
    world.model.cam_mode[cam] = int(mujoco.mjtCamLight.mjCAMLIGHT_FIXED)
    # Camera poses in data are derived in the kinematics pass (the state is not changed).
    mujoco.mj_kinematics(world.model, world.data)
    mujoco.mj_camlight(world.model, world.data)


def _link_labels(world: World, seg: Vec) -> Any:
    """(H, W) link index 1..n per pixel (0: not a link) from MuJoCo's (objid, objtype) image."""
    geom_link = np.zeros(world.model.ngeom + 1, dtype=np.int32)
    for i, link in enumerate(world.obj.links):
        geom_link[world.model.geom(f"{link}_geom").id] = i + 1
    ids, types = seg[..., 0], seg[..., 1]
    is_geom = (types == int(mujoco.mjtObj.mjOBJ_GEOM)) & (ids >= 0)
    labels = np.zeros(ids.shape, dtype=np.int32)
    labels[is_geom] = geom_link[ids[is_geom]]
    return labels


def colour_labels(labels: Vec) -> Vec:
    """(H, W, 3) uint8 image: each link in its colour, background black."""
    palette = np.zeros((int(labels.max()) + 1, 3))
    for i in range(1, len(palette)):
        palette[i] = LINK_COLOURS[(i - 1) % len(LINK_COLOURS)]
    return (palette[labels] * 255).astype(np.uint8)


def depth_image(depth: Vec) -> Vec:
    """(H, W) uint8 image of a depth map [m]: near is bright, far dark."""
    finite = depth[np.isfinite(depth)]
    if finite.size:
        # The sky sits at the far clipping plane: scale to the nearer part of the scene.
        near = finite[finite < 0.98 * finite.max()]
        near = near if near.size else finite
        lo, hi = float(np.percentile(near, 0.5)), float(np.percentile(near, 99.5))
    else:
        lo, hi = 0.0, 1.0
    scaled = 1.0 - (depth - lo) / max(hi - lo, 1e-9)
    return (np.clip(scaled, 0.0, 1.0) * 255).astype(np.uint8)
