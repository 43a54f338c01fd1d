"""Draw an articulated object in 3D (matplotlib, Agg backend): the clamp, coloured links, joints,
and optionally a target configuration as a translucent ghost."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from artiplan.model import ArticulatedObject, Configuration, forward_kinematics


def _link_colours(n: int) -> list[Any]:
    import matplotlib

    cmap = matplotlib.colormaps["viridis"]
    return [cmap(i / max(n - 1, 1)) for i in range(n)]


def _draw_clamp(ax: Any, base: NDArray[np.float64], size: float) -> None:
    """A translucent grey block (the fixture) around L1's base end."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * size / 2
    corners = corners + base
    faces = [
        [corners[i] for i in face]
        for face in (
            (0, 1, 3, 2),
            (4, 5, 7, 6),
            (0, 1, 5, 4),
            (2, 3, 7, 6),
            (0, 2, 6, 4),
            (1, 3, 7, 5),
        )
    ]
    ax.add_collection3d(
        Poly3DCollection(faces, facecolor="0.4", edgecolor="0.2", alpha=0.35, linewidths=0.5)
    )
    ax.plot([], [], color="0.4", alpha=0.5, linewidth=6, label="clamp")


def _draw_chain(
    ax: Any, points: NDArray[np.float64], width: float, alpha: float, label: str | None
) -> None:
    colours = _link_colours(len(points) - 1)
    for i, colour in enumerate(colours):
        seg = points[i : i + 2]
        ax.plot(
            seg[:, 0],
            seg[:, 1],
            seg[:, 2],
            color=colour,
            linewidth=width,
            alpha=alpha,
            solid_capstyle="round",
            label=f"L{i + 1}" if label == "links" else None,
        )
    ax.scatter(points[1:-1, 0], points[1:-1, 1], points[1:-1, 2], color="black", s=18, alpha=alpha)
    ax.scatter(*points[-1], color="red", s=24, alpha=alpha, marker="^")


def _equal_axes(ax: Any, points: NDArray[np.float64]) -> None:
    centre = (points.max(axis=0) + points.min(axis=0)) / 2
    radius = max(float(np.ptp(points, axis=0).max()) / 2, 0.05) * 1.1
    ax.set_xlim(centre[0] - radius, centre[0] + radius)
    ax.set_ylim(centre[1] - radius, centre[1] + radius)
    ax.set_zlim(centre[2] - radius, centre[2] + radius)
    ax.set_box_aspect((1, 1, 1))


def draw_configuration(
    obj: ArticulatedObject,
    conf: Configuration,
    out: str | Path,
    target: Configuration | None = None,
    title: str | None = None,
) -> Path:
    """Write a PNG of ``conf`` (and ``target`` as a ghost) to ``out``.

    Args:
        obj: The object (link length [m], base position [m]).
        conf: Configuration to draw [deg].
        out: PNG path.
        target: Optional target configuration, drawn translucent.
        title: Figure title (default: the number of links).

    Returns:
        The path written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    points = forward_kinematics(obj, conf)
    every = [points]
    fig = plt.figure(figsize=(6.4, 6.0), dpi=110)
    ax = fig.add_subplot(projection="3d")
    _draw_clamp(ax, np.asarray(obj.base_position, dtype=float), obj.thickness * 1.6)
    width = max(obj.thickness * 200, 3.0)
    if target is not None:
        ghost = forward_kinematics(obj, target)
        every.append(ghost)
        _draw_chain(ax, ghost, width, 0.25, None)
        ax.plot([], [], color="0.5", alpha=0.35, linewidth=width, label="target (ghost)")
    _draw_chain(ax, points, width, 1.0, "links")
    _equal_axes(ax, np.vstack(every))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.view_init(elev=20, azim=-60)
    ax.legend(loc="upper left", fontsize=7, ncols=2)
    ax.set_title(title or f"{obj.n_links}-link object (L1 clamped)")
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out)
    plt.close(fig)
    return out
