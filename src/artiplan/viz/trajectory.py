"""Plot a simulated plan: fluents (angles) over time, happenings as vertical lines, events
labelled. Matplotlib with the Agg backend (no display needed)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from artiplan.pddl.task import fluent_column
from artiplan.semantics.trajectory import Trajectory

#: Points per flow segment: segments are polynomials, 60 points draw them smoothly.
_POINTS_PER_SEGMENT = 60


def _fluents_to_plot(traj: Trajectory) -> list[int]:
    """Angles if there are any, else every fluent that changes."""
    angles = [i for i, f in enumerate(traj.fluents) if f.strip("( ").lower().startswith("angle")]
    if angles:
        return angles
    first = traj.rows[0].values if traj.rows else ()
    return [i for i in range(len(traj.fluents)) if any(r.values[i] != first[i] for r in traj.rows)]


def _curve(traj: Trajectory, end: float) -> tuple[list[float], list[tuple[float, ...]]]:
    """Times and values along every segment, with a NaN break between segments (the jumps of
    events and happenings are not drawn as slopes)."""
    times: list[float] = []
    values: list[tuple[float, ...]] = []
    nan = (math.nan,) * len(traj.fluents)
    for seg in traj.segments:
        t1 = min(seg.t1, end)
        if t1 < seg.t0:
            continue
        n = _POINTS_PER_SEGMENT if t1 > seg.t0 else 1
        for k in range(n + 1):
            t = seg.t0 + (t1 - seg.t0) * k / n
            times.append(t)
            values.append(seg.values_at(t))
        times.append(t1)
        values.append(nan)
    return times, values


def _mark(ax: Any, traj: Trajectory, kind: str, color: str, ls: str, y: float, va: str) -> None:
    """Vertical lines at the rows of ``kind``, one label per instant (names stacked)."""
    by_time: dict[float, list[str]] = {}
    for r in traj.rows:
        if r.kind == kind:
            by_time.setdefault(round(r.time, 6), []).append(r.happening)
    for t, names in by_time.items():
        ax.axvline(t, color=color, ls=ls, lw=0.8)
        ax.text(
            t,
            y,
            " " + "\n ".join(names),
            rotation=90,
            va=va,
            ha="right",
            fontsize=6,
            color=color,
            transform=ax.get_xaxis_transform(),
        )


def plot_trajectory(traj: Trajectory, path: str | Path, title: str = "") -> None:
    """Write a PNG of the angles over time to ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    last = max([traj.end or 0.0, *(r.time for r in traj.rows)])
    end = last + max(1.0, 0.05 * last)
    times, values = _curve(traj, end)
    fig, ax = plt.subplots(figsize=(10, 5.5), dpi=110)
    for i in _fluents_to_plot(traj):
        ax.plot(times, [v[i] for v in values], label=fluent_column(traj.fluents[i]), lw=1.6)
    _mark(ax, traj, "action", color="0.3", ls="--", y=0.985, va="top")
    _mark(ax, traj, "event", color="tab:red", ls=":", y=0.015, va="bottom")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("angle [deg]")
    ax.set_xlim(0.0, end)
    ax.set_title(title or "simulated plan")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
