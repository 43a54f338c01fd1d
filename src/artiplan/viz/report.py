"""Figures of the benchmark report: the paper's PAR10 figure and a cactus plot.

Matplotlib with the Agg backend (no display needed). Each figure is written as PNG and SVG.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

_LABELS = {"ng": "NG", "ucm": "UCM", "uacm": "UACM"}
_MARKERS = ("o", "s", "^", "D", "v", "P", "X")


def _pyplot():  # type: ignore[no-untyped-def]
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def variant_label(variant: str) -> str:
    """``ucm-0.1`` -> ``UCM 0.1``."""
    model, _, param = variant.partition("-")
    return f"{_LABELS.get(model, model.upper())} {param}".strip()


def _save(fig: object, base: Path) -> list[Path]:
    paths = [base.with_suffix(".png"), base.with_suffix(".svg")]
    for path in paths:
        fig.savefig(path, dpi=150, bbox_inches="tight")  # type: ignore[attr-defined]
    return paths


def plot_par10(
    scores: Mapping[str, Mapping[tuple[str, int], float]],
    variants: Sequence[str],
    sizes: Sequence[int],
    limit: float,
    base: Path,
) -> list[Path]:
    """PAR10 [s] per size, one line per model variant, one panel per planner.

    Args:
        scores: planner -> (variant, size) -> PAR10 [s].
        variants: the lines to draw (the paper: NG, UCM 0.1, UACM 0.1).
        sizes: the x axis (number of links).
        limit: the CPU-time limit [s]; 10 x limit is the ceiling of the y axis.
        base: output path without suffix; ``.png`` and ``.svg`` are written.
    """
    plt = _pyplot()
    names = list(scores)
    fig, axes = plt.subplots(1, len(names), figsize=(4.2 * len(names), 3.6), sharey=True,
                             squeeze=False)
    for ax, planner in zip(axes[0], names, strict=True):
        for i, variant in enumerate(variants):
            xs = [s for s in sizes if (variant, s) in scores[planner]]
            ys = [scores[planner][(variant, s)] for s in xs]
            if xs:  # one color and marker per variant in every panel
                ax.plot(xs, ys, marker=_MARKERS[i % len(_MARKERS)], color=f"C{i}",
                        label=variant_label(variant))
        ax.axhline(10 * limit, color="grey", linestyle=":", linewidth=1)
        ax.set_yscale("log")
        ax.set_title(planner)
        ax.set_xlabel("size (links)")
        ax.set_xticks(list(sizes))
        ax.grid(True, which="major", alpha=0.3)
    axes[0][0].set_ylabel(f"PAR10 [CPU s] (unsolved = {10 * limit:g} s)")
    handles: dict[str, object] = {}
    for ax in axes[0]:
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            handles.setdefault(label, handle)
    fig.suptitle(f"PAR10 per size, CPU-time limit {limit:g} s", y=0.99)
    fig.tight_layout(rect=(0, 0, 1, 0.86))
    fig.legend(list(handles.values()), list(handles), loc="upper center", fontsize=8,
               ncol=min(len(handles), 6), bbox_to_anchor=(0.5, 0.93), frameon=False)
    paths = _save(fig, base)
    plt.close(fig)
    return paths


def plot_cactus(
    times: Mapping[str, Sequence[float]], total: int, limit: float, base: Path
) -> list[Path]:
    """Cactus plot: problems solved (x) within a CPU time (y, log), one line per planner.

    Args:
        times: planner -> sorted CPU times of its solved runs [s].
        total: the number of problems each planner ran (the x axis ends there).
        limit: the CPU-time limit [s] (a dotted line).
        base: output path without suffix.
    """
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    for i, (planner, values) in enumerate(times.items()):
        xs = list(range(1, len(values) + 1))
        ax.plot(xs, values, marker=_MARKERS[i % len(_MARKERS)], markersize=3,
                label=f"{planner} ({len(values)} solved)")
    ax.axhline(limit, color="grey", linestyle=":", linewidth=1, label=f"limit {limit:g} s")
    ax.set_yscale("log")
    ax.set_xlim(0, max(total, 1) + 1)
    ax.set_xlabel(f"problems solved (of {total})")
    ax.set_ylabel("CPU time [s]")
    ax.set_title("Cactus plot: valid plans found within a CPU time")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    paths = _save(fig, base)
    plt.close(fig)
    return paths


def plot_ratio(
    ratios: Mapping[str, Sequence[tuple[float, float]]], base: Path, limit: float
) -> list[Path]:
    """Scatter of per-problem CPU time, planner a (y) against b (x), log-log, with y = x.

    Args:
        ratios: "a (y) vs b (x)" -> (time b, time a) pairs [s] on problems both solved.
        base: output path without suffix.
        limit: the CPU-time limit [s] (the axes end there).
    """
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(5, 5))
    low = limit
    for i, (label, points) in enumerate(ratios.items()):
        if points:
            xs, ys = zip(*points, strict=True)
            low = min(low, *xs, *ys)
            ax.scatter(xs, ys, s=14, marker=_MARKERS[i % len(_MARKERS)], label=label, alpha=0.7)
    low = max(low / 2, 1e-3)
    ax.plot([low, limit], [low, limit], color="grey", linewidth=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(low, limit * 1.2)
    ax.set_ylim(low, limit * 1.2)
    ax.set_xlabel("CPU time of planner b [s]")
    ax.set_ylabel("CPU time of planner a [s]")
    ax.set_title("Per problem solved by both: below the line, a is faster", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    paths = _save(fig, base)
    plt.close(fig)
    return paths


def write_report(rows: Sequence[dict[str, Any]], outdir: Path, source: str = "") -> list[Path]:
    """Write the whole report under ``outdir``: Table 1 (Markdown, LaTeX) per planner, PAR10
    and cactus figures (PNG, SVG), per-problem comparisons, a CSV of all runs and ``index.md``.

    Args:
        rows: result rows (``artiplan bench``'s JSON Lines); the last row per run counts.
        outdir: the report folder (created).
        source: where the rows came from (named in the index).

    Returns:
        Every file written, ``index.md`` last.
    """
    from artiplan.bench import aggregate as agg
    from artiplan.bench import tables

    data = agg.latest_rows(rows)
    outdir.mkdir(parents=True, exist_ok=True)
    names, sizes, variants = agg.planners(data), agg.sizes(data), agg.variants(data)
    limit = agg.time_limit(data)
    written: list[Path] = []
    index = _index_head(data, names, limit, source)

    def put(name: str, text: str) -> Path:
        path = outdir / name
        path.write_text(text)
        written.append(path)
        return path

    summaries = [agg.summarise(data, a, b, limit) for a, b in _pairs_of(names)]
    index += ["## Summary", "", tables.summary_markdown(summaries, limit)]
    counts = {n: agg.status_counts(data, n) for n in names}
    index += ["## Runs by status", "", tables.status_markdown(counts)]
    title = "## Table 1: mean CPU time of solved runs [s] (percentage solved"
    title += " / percentage whose plan stock VAL accepts too)" if agg.has_val(data) else ")"
    index += [title, ""]
    for name in names:
        cells = agg.table1(data, name)
        md = tables.table1_markdown(cells, variants, sizes)
        caption = (f"Results achieved by {name} (CPU-time limit {limit:g} s): average run-time "
                   "of solved instances (percentage of solved instances).")
        put(f"table1-{name}.md", f"# Table 1: {name}\n\n{md}")
        put(f"table1-{name}.tex", tables.table1_latex(cells, variants, sizes, caption))
        index += [f"### {name}", "", md,
                  f"[Markdown](table1-{name}.md), [LaTeX](table1-{name}.tex)", ""]
    index += ["### For reference: the paper's Table 1 (ENHSP, 300 CPU-s limit, 8 GB, i7-6900K)",
              "", tables.paper_table1_markdown()]
    par = {n: agg.par10(data, n, limit) for n in names}
    shown = [v for v in agg.PAR10_VARIANTS if v in variants] or variants
    written += plot_par10(par, shown, sizes, limit, outdir / "par10")
    written += plot_par10(par, variants, sizes, limit, outdir / "par10-all")
    index += ["## PAR10 (the paper's figure: NG, UCM 0.1, UACM 0.1)", "",
              "![PAR10](par10.png)", "", "All six model settings: [par10-all.png](par10-all.png)",
              ""]
    for name in names:
        index += [f"PAR10 [s] of {name}:", "", tables.par10_markdown(par[name], variants, sizes)]
    total = max((sum(1 for r in data if r["planner"] == n) for n in names), default=0)
    written += plot_cactus({n: agg.cactus(data, n) for n in names}, total, limit,
                           outdir / "cactus")
    index += ["## Cactus plot", "", "![cactus](cactus.png)", ""]
    index += _comparisons(data, names, limit, outdir, put, written)
    put("runs.csv", tables.rows_csv(data))
    index += ["All runs (no plans): [runs.csv](runs.csv).", ""]
    put("index.md", "\n".join(index))
    return written


def _pairs_of(names: Sequence[str]) -> list[tuple[str, str]]:
    """artiplan against each other planner, then the others among themselves."""
    return [(a, b) for i, a in enumerate(names) for b in names[i + 1:]]


def _index_head(
    data: Sequence[dict[str, Any]], names: Sequence[str], limit: float, source: str
) -> list[str]:
    from datetime import datetime, timezone

    hosts = sorted({str(r.get("host", "")) for r in data})
    memory = max(float(r.get("memory_limit") or 0) for r in data)
    return [
        "# Benchmark report", "",
        f"Source: `{source}` ({len(data)} runs); planners: {', '.join(names)}; "
        f"CPU-time limit {limit:g} s, memory limit {memory:g} MiB per run; hosts: "
        f"{', '.join(hosts)}. Generated {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC.", "",
        "Times are CPU seconds of the planner process (as in the paper). A run counts as solved "
        "only if artiplan's validator (VAL's semantics, tolerance 0.001) accepts its plan; "
        "`invalid` rows are plans it rejected.", "",
    ]


def _comparisons(
    data: Sequence[dict[str, Any]],
    names: Sequence[str],
    limit: float,
    outdir: Path,
    put: Callable[[str, str], Path],
    written: list[Path],
) -> list[str]:
    from artiplan.bench import aggregate as agg
    from artiplan.bench import tables

    lines = ["## Per-problem comparisons", ""]
    points: dict[str, list[tuple[float, float]]] = {}
    for a, b in _pairs_of(names):
        found = agg.pairs(data, a, b)
        name = f"compare-{a}-vs-{b}.md"
        put(name, f"# {a} vs {b}: per problem\n\n" + tables.comparison_markdown(found, a, b))
        lines.append(f"- [{a} vs {b}]({name}): time, makespan and actions, with ratios {a} / {b}")
        points[f"a = {a}, b = {b}"] = [
            (float(p.b["cpu_s"]), float(p.a["cpu_s"]))
            for p in found if agg.solved(p.a) and agg.solved(p.b)
        ]
    if points:
        written += plot_ratio(points, outdir / "time-scatter", limit)
        lines += ["", "![per-problem CPU time](time-scatter.png)", ""]
    return lines
