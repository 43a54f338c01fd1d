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


def render(world: World, camera: str, kind: str, width: int, height: int) -> Vec:
    """One image; see :meth:`artiplan.world.scene.World.render`."""
    if kind not in KINDS:
        raise ValueError(f"unknown image kind {kind!r}; valid kinds: {', '.join(KINDS)}")
    model = world.model
    if mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_CAMERA, camera) < 0:
        names = [model.camera(i).name for i in range(model.ncam)]
        raise ValueError(f"unknown camera {camera!r}; cameras: {', '.join(names)}")
    renderer = mujoco.Renderer(model, height=height, width=width)
    try:
        if kind == "depth":
            renderer.enable_depth_rendering()
        elif kind == "segmentation":
            renderer.enable_segmentation_rendering()
        renderer.update_scene(world.data, camera=camera)
        image = renderer.render()
    finally:
        renderer.close()
    if kind == "segmentation":
        return _link_labels(world, image)
    return np.asarray(image)


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
    lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    scaled = 1.0 - (depth - lo) / max(hi - lo, 1e-9)
    return (np.clip(scaled, 0.0, 1.0) * 255).astype(np.uint8)
