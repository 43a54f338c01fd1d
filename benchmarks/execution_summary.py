"""Summarise benchmarks/execution/loop-*.jsonl (from execution_loop.py): a Markdown table on
stdout and a bar chart benchmarks/execution/loop.png.

Usage: .venv/bin/python benchmarks/execution_summary.py
"""

from __future__ import annotations

import json
import statistics
from pathlib import Path

HERE = Path(__file__).resolve().parent / "execution"


def main() -> None:
    rows = []
    for path in sorted(HERE.glob("loop-*.jsonl")):
        runs = [json.loads(line) for line in path.read_text().splitlines() if line.strip()]
        if not runs:
            continue
        lat = [x for r in runs for x in r["latency_wall_s"]]
        rows.append({
            "variant": path.stem.removeprefix("loop-"), "runs": len(runs),
            "success": sum(r["success"] for r in runs),
            "ok_le5": sum(r["success"] and r["replans"] <= 5 for r in runs),
            "replans_mean": statistics.mean(r["replans"] for r in runs),
            "replans_max": max(r["replans"] for r in runs),
            "pushes": sum(r["interventions"] for r in runs),
            "lat_med": statistics.median(lat) if lat else float("nan"),
            "lat_max": max(lat) if lat else float("nan"),
            "sim_mean": statistics.mean(r["sim_s"] for r in runs),
            "err_mean": statistics.mean(r["max_goal_error"] for r in runs),
            "hands": runs[0]["hands"], "model": runs[0]["model"],
        })
    print("| variant | hands | model | runs | success | re-plans mean / max | pushes | "
          "re-plan latency median / max [s] | sim time mean [s] | final goal error mean [deg] |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['variant']} | {r['hands']} | {r['model']} | {r['runs']} | "
              f"{r['success']}/{r['runs']} ({100 * r['success'] / r['runs']:.0f}%) | "
              f"{r['replans_mean']:.2f} / {r['replans_max']} | {r['pushes']} | "
              f"{r['lat_med']:.3f} / {r['lat_max']:.3f} | {r['sim_mean']:.1f} | "
              f"{r['err_mean']:.2f} |")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4))
    x = range(len(rows))
    ax.bar(x, [100 * r["success"] / r["runs"] for r in rows], color="tab:green", label="success")
    ax2 = ax.twinx()
    ax2.plot(list(x), [r["replans_mean"] for r in rows], "o-", color="tab:red",
             label="re-plans (mean)")
    ax.set_xticks(list(x), [r["variant"] for r in rows], rotation=20, fontsize=8)
    ax.set_ylabel("goal reached [%]")
    ax2.set_ylabel("re-plans per run (mean)")
    ax.axhline(95, color="0.5", ls="--", lw=0.8)
    ax.set_title("closed loop over 20 seeded tasks (window goals)")
    fig.tight_layout()
    fig.savefig(HERE / "loop.png", dpi=100)


if __name__ == "__main__":
    main()
