"""Pictures of a closed-loop run: predicted vs perceived angles and errors over time, camera
snapshots at every action (like the paper's Fig. 4) and an animation from the overhead camera.

Rendering needs ``MUJOCO_GL=egl`` (or ``osmesa``) set before MuJoCo is imported.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from artiplan.world import World

_HAPPENING, _REPLAN, _PUSH = "0.6", "tab:red", "tab:orange"
#: Theta is not drawn where gamma is this near [deg] a pole (0, 180, 360): it is not observable.
POLE_DEG = 3.0
#: Colours of the planned grasp-point traces in the snapshots, per hand (RGBA).
TRACE_RGBA = {"left": (1.0, 0.55, 0.0, 1.0), "right": (0.1, 0.45, 1.0, 1.0)}


def cover_flips(thetas: list[float], gammas: list[float], tol: float = 20.0) -> set[int]:
    """Indices k where sample k is the other double-cover representation of a direction near
    sample k-1's, (t, g) -> (t + 180, 360 - g) within ``tol`` [deg]: not a motion, a change
    of representation (plots break the line there)."""
    out = set()
    for k in range(1, len(thetas)):
        dt = abs((thetas[k] - thetas[k - 1] + 180.0) % 360.0 - 180.0)
        g = (gammas[k] + gammas[k - 1]) % 360.0  # 360 - g_prev + g_prev: 0 (or 360)
        if abs(dt - 180.0) < tol and min(g, 360.0 - g) < tol:
            out.add(k)
    return out


def wrap_breaks(
    ts: list[float], vs: list[float], breaks: set[int] | None = None
) -> tuple[list[float], list[float]]:
    """An angle series [deg, in [0, 360)] ready to plot: where it wraps through 0/360 (a jump
    of more than 270 deg between samples, i.e. less than 90 deg the short way) the line runs
    to the edge of the band at the interpolated crossing time and on from the other edge;
    other jumps of more than 180 deg (a change of the double-cover representation, or a pole)
    break the line, and so do the samples in ``breaks`` (:func:`cover_flips`). Returns
    (times, values) with NaN at the breaks."""
    out_t: list[float] = []
    out_v: list[float] = []
    for k, (t, v) in enumerate(zip(ts, vs, strict=True)):
        prev = vs[k - 1] if k else math.nan
        jump = abs(v - prev) if k and not math.isnan(prev) and not math.isnan(v) else 0.0
        if breaks and k in breaks:
            out_t.append(t)
            out_v.append(math.nan)
        elif jump > 270.0:
            up = v < prev  # e.g. 350 -> 10: it went up through 360
            unwrapped = v + 360.0 if up else v - 360.0
            edge = 360.0 if up else 0.0
            tc = ts[k - 1] + (edge - prev) / (unwrapped - prev) * (t - ts[k - 1])
            out_t += [tc, tc, tc]
            out_v += [edge, math.nan, 360.0 - edge]
        elif jump > 180.0:
            out_t.append(t)
            out_v.append(math.nan)
        out_t.append(t)
        out_v.append(v)
    return out_t, out_v


def _mark_events(ax: Any, log: dict[str, Any]) -> None:
    for h in log["happenings"]:
        ax.axvline(h["time"], color=_HAPPENING, lw=0.6, ls=":")
    for r in log["replans"]:
        ax.axvline(r["time"], color=_REPLAN, lw=1.2)
    for i in log["interventions"]:
        ax.axvline(i["time"], color=_PUSH, lw=1.2, ls="--")


def _event_handles(log: dict[str, Any]) -> list[Any]:
    """Legend entries of the vertical lines that are in the plot."""
    from matplotlib.lines import Line2D

    out = [Line2D([], [], color=_HAPPENING, lw=0.8, ls=":", label="happening")]
    if log["replans"]:
        out.append(Line2D([], [], color=_REPLAN, lw=1.2, label="re-plan"))
    if log["interventions"]:
        out.append(Line2D([], [], color=_PUSH, lw=1.2, ls="--", label="human push"))
    return out


def _off_pole(vs: list[float], gammas: list[float]) -> list[float]:
    """``vs`` (theta) with NaN where gamma is within POLE_DEG of a pole."""
    return [math.nan if min(abs(g % 180.0), 180.0 - abs(g % 180.0)) < POLE_DEG else v
            for v, g in zip(vs, gammas, strict=True)]


def plot_run(log: dict[str, Any], path: str | Path, title: str = "") -> Path:
    """Predicted (dashed) vs perceived (solid) theta and gamma of every moving link, and the
    per-link direction error with the monitor's thresholds. Goal links are drawn thick with
    their target angles (dotted), the other links thin; theta is left out near the poles
    (where it is not observable); a wrap through 0/360 leaves at one edge and comes back
    at the other (:func:`wrap_breaks`). Happenings dotted grey, re-plans red, human
    interventions orange dashed (in the legend). Returns the PNG path."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    samples = log["samples"]
    n = len(log["initial"]["theta"])
    goals = set(log.get("goal_links", []))
    ts = [s["time"] for s in samples]
    fig, axes = plt.subplots(3, 1, figsize=(10, 9.5), sharex=True)
    colours = plt.get_cmap("tab10")
    for ax, key, label in ((axes[0], "theta", "theta (xy-axes) [deg]"),
                           (axes[1], "gamma", "gamma (z-axis) [deg]")):
        for i in range(1, n):
            c, goal = colours(i % 10), f"L{i + 1}" in goals
            lw, alpha = (2.2, 1.0) if goal else (0.9, 0.55)
            for src, ls in (("predicted", "--"), ("perceived", "-")):
                vs = [s[src][key][i] for s in samples]
                gs = [s[src]["gamma"][i] for s in samples]
                flips = cover_flips([s[src]["theta"][i] for s in samples], gs)
                if key == "theta":
                    vs = _off_pole(vs, gs)
                t, v = wrap_breaks(ts, vs, flips)
                name = f"L{i + 1}{' (goal)' if goal else ''} {src}"
                ax.plot(t, v, ls=ls, color=c, lw=lw, alpha=alpha,
                        label=name if key == "theta" else None)
            if goal and ts:
                ax.axhline(log["target"][key][i], color=c, lw=1.0, ls=":",
                           label=f"L{i + 1} target" if key == "theta" else None)
        ax.set_ylabel(label)
        ax.set_ylim(-5, 365)
        _mark_events(ax, log)
    axes[0].legend(ncol=4, fontsize=7, loc="upper right")
    axes[0].set_title(f"theta not drawn within {POLE_DEG:g} deg of a pole (unobservable)",
                      fontsize=8, loc="left")
    for i in range(1, n):
        goal = f"L{i + 1}" in goals
        errs = [s["errors"][i] for s in samples]
        axes[2].plot(ts, errs, color=colours(i % 10), lw=2.0 if goal else 0.9,
                     alpha=1.0 if goal else 0.55, label=f"L{i + 1}{' (goal)' if goal else ''}")
    settings = log["settings"]
    axes[2].axhline(settings["threshold_deg"], color=_REPLAN, lw=0.8, ls="--",
                    label="threshold (goal links)")
    _mark_events(axes[2], log)
    axes[2].set_ylabel("direction error [deg]")
    axes[2].set_xlabel("simulated time [s]")
    axes[2].set_yscale("symlog", linthresh=10.0)
    handles, _ = axes[2].get_legend_handles_labels()
    axes[2].legend(handles=handles + _event_handles(log), ncol=5, fontsize=7, loc="upper right")
    verdict = "goal reached" if log["success"] else "goal NOT reached"
    collisions = log.get("collisions")
    extra = f", {len(collisions)} arm collision(s)" if collisions is not None and \
        log["settings"].get("hands") == "baxter" else ""
    fig.suptitle(title or f"closed loop: {verdict}, {len(log['replans'])} re-plan(s){extra}")
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


class FrameRecorder:
    """Records camera frames during a run (pass :meth:`observe` as the loop's observer).

    Every ``every``-th monitor percept becomes an animation frame (overhead camera); every
    action, intervention and the final check also becomes a snapshot (overhead and
    perspective side by side, captioned).
    """

    def __init__(self, world: World, width: int = 320, height: int = 240, every: int = 1) -> None:
        import mujoco

        self.renderer = mujoco.Renderer(world.model, height=height, width=width)
        self.every, self._count = every, 0
        #: Planned grasp-point traces already drawn (``hands.last_paths`` of Baxter).
        self._paths_seen = 0
        self._traces: list[dict[str, list[np.ndarray]]] = []
        self.frames: list[np.ndarray] = []
        self.snapshots: list[tuple[float, str, np.ndarray]] = []
        # Free cameras framed on the object (the scene's fixed cameras frame the whole robot,
        # where a 15 cm link is a few pixels): "overhead" looks straight down on the base.
        reach = world.obj.n_links * world.obj.link_length
        self.cameras: dict[str, Any] = {}
        centre = 0.5 * (np.asarray(world.base_position) + world.link_centres().mean(axis=0))
        # Baxter stands behind the object (+x faces it): look at it from the front.
        side = 180.0 if world.hands.kind == "baxter" else 135.0
        for name, azimuth, elevation, dist in (("overhead", 90.0, -89.9, 2.2),
                                               ("perspective", side, -25.0, 2.6)):
            cam = mujoco.MjvCamera()
            cam.type = mujoco.mjtCamera.mjCAMERA_FREE
            cam.lookat[:] = centre
            cam.distance, cam.azimuth, cam.elevation = dist * reach, azimuth, elevation
            self.cameras[name] = cam

    def _image(self, world: World, camera: str, traces: bool = False) -> np.ndarray:
        self.renderer.update_scene(world.data, camera=self.cameras[camera])
        if traces:
            for paths in self._traces:
                _draw_traces(self.renderer.scene, paths)
        return np.asarray(self.renderer.render()).copy()

    def observe(self, world: World, kind: str, label: str) -> None:
        """The loop's observer hook."""
        if kind == "monitor":
            self._count += 1
            if (self._count - 1) % self.every == 0:
                self.frames.append(_caption(self._image(world, "overhead"),
                                            f"t = {world.time:5.1f} s"))
            return
        paths = getattr(world.hands, "last_paths", [])
        self._traces = list(paths[self._paths_seen:])  # the motions of this action
        self._paths_seen = len(paths)
        pair = np.concatenate([self._image(world, "overhead", True),
                               self._image(world, "perspective", True)], axis=1)
        note = "  (lines: planned hand paths)" if self._traces else ""
        self.snapshots.append((world.time, label, _caption(pair, f"t = {world.time:.2f} s  "
                                                                 f"{label}{note}")))
        if kind == "intervention":  # make the push visible in the animation too
            self.frames.append(_caption(self._image(world, "overhead"),
                                        f"t = {world.time:5.1f} s  human push"))

    def write_gif(self, path: str | Path, fps: float = 8.0) -> Path:
        """The animation (GIF, looping)."""
        import imageio.v3 as iio

        out = Path(path)
        iio.imwrite(out, np.stack(self.frames), duration=1000.0 / fps, loop=0)
        return out

    def write_snapshots(self, folder: str | Path) -> list[Path]:
        """One PNG per action/intervention/final check, numbered in order."""
        import imageio.v3 as iio

        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        written = []
        for k, (_t, label, img) in enumerate(self.snapshots):
            slug = "".join(ch if ch.isalnum() else "-" for ch in label.strip("()"))[:40]
            p = out / f"{k:02d}-{slug.strip('-')}.png"
            iio.imwrite(p, img)
            written.append(p)
        return written

    def close(self) -> None:
        self.renderer.close()


def _draw_traces(scene: Any, paths: dict[str, list[np.ndarray]]) -> None:
    """Add each hand's planned grasp-point trace to ``scene`` as a chain of thin capsules
    (and a sphere where it ends: the grasp)."""
    import mujoco

    for hand, pts in paths.items():
        rgba = np.array(TRACE_RGBA.get(hand, (1.0, 1.0, 1.0, 1.0)), dtype=np.float32)
        for a, b in zip(pts, pts[1:], strict=False):
            if scene.ngeom >= scene.maxgeom or np.linalg.norm(b - a) < 1e-6:
                continue
            g = scene.geoms[scene.ngeom]
            mujoco.mjv_initGeom(g, mujoco.mjtGeom.mjGEOM_CAPSULE, np.zeros(3), np.zeros(3),
                                np.eye(3).ravel(), rgba)
            mujoco.mjv_connector(g, mujoco.mjtGeom.mjGEOM_CAPSULE, 0.004, a, b)
            scene.ngeom += 1
        if pts and scene.ngeom < scene.maxgeom:
            mujoco.mjv_initGeom(scene.geoms[scene.ngeom], mujoco.mjtGeom.mjGEOM_SPHERE,
                                np.full(3, 0.012), pts[-1], np.eye(3).ravel(), rgba)
            scene.ngeom += 1


def _caption(img: np.ndarray, text: str) -> np.ndarray:
    """The image with a caption strip on top (PIL's default font)."""
    from PIL import Image, ImageDraw

    strip = 16
    canvas = Image.new("RGB", (img.shape[1], img.shape[0] + strip), "white")
    canvas.paste(Image.fromarray(img), (0, strip))
    ImageDraw.Draw(canvas).text((4, 2), text, fill="black")
    return np.asarray(canvas)


def contact_sheet(snapshots: list[Path], path: str | Path, columns: int = 2) -> Path:
    """All snapshots in one grid image (the paper's Fig. 4 layout)."""
    import imageio.v3 as iio

    imgs = [np.asarray(iio.imread(p))[..., :3] for p in snapshots]
    h = max(i.shape[0] for i in imgs)
    w = max(i.shape[1] for i in imgs)
    rows = math.ceil(len(imgs) / columns)
    sheet = np.full((rows * h, columns * w, 3), 255, dtype=np.uint8)
    for k, img in enumerate(imgs):
        r, c = divmod(k, columns)
        sheet[r * h : r * h + img.shape[0], c * w : c * w + img.shape[1]] = img
    out = Path(path)
    iio.imwrite(out, sheet)
    return out


def plot_fidelity(table: list[dict[str, Any]], folder: str | Path) -> list[Path]:
    """Bar charts of the fidelity summary: open-loop prediction errors (RMS and at the end) per
    model and parameters, and goal/success rates open-loop vs re-planning, per preset and size.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out = Path(folder)
    groups = sorted({(r["preset"], r["size"]) for r in table})
    paths = []
    for name, series, ylabel in (
        ("fidelity-errors.png", (("rms_deg", "RMS"), ("end_deg", "at the end")),
         "direction error vs prediction [deg]"),
        ("fidelity-success.png", (("open_goal_pct", "open loop"),
                                  ("closed_success_pct", "re-planning")), "goal reached [%]"),
    ):
        fig, axes = plt.subplots(1, len(groups), figsize=(5 * len(groups), 4), squeeze=False)
        for ax, (preset, size) in zip(axes[0], groups, strict=True):
            rows = [r for r in table if r["preset"] == preset and r["size"] == size]
            labels = [f"{r['model'].upper()}\n" + r["calibration"].replace(", ", "\n")
                      for r in rows]
            x = np.arange(len(rows))
            for k, (key, lab) in enumerate(series):
                vals = [r[key] if r[key] is not None else 0.0 for r in rows]
                ax.bar(x + (k - 0.5) * 0.38, vals, 0.38, label=lab)
            ax.set_xticks(x, labels, fontsize=8)
            ax.set_title(f"{size} links, {preset}")
            ax.set_ylabel(ylabel)
            ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(out / name, dpi=100)
        plt.close(fig)
        paths.append(out / name)
    return paths
