"""``artiplan fidelity -o DIR``: measure each gravity model's prediction against physics.

Writes ``runs.jsonl`` (one row a run), ``fidelity.csv`` and ``fidelity.md`` (the summary
table) and plots (``fidelity-errors.png``, ``fidelity-success.png``) to DIR.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
from pathlib import Path
from typing import Any

from artiplan.errors import UsageError

COLUMNS = ("preset", "size", "model", "calibration", "tasks", "planned", "rms_deg", "max_deg",
           "end_deg", "goal_rms_deg", "goal_end_deg", "open_goal_pct", "closed_success_pct",
           "closed_replans", "closed_sim_s", "closed_wall_s")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--tasks", type=int, default=20, help="tasks per size (default 20)")
    parser.add_argument("--sizes", default="4,6", help="object sizes (default 4,6)")
    parser.add_argument("--preset", choices=("stiff", "loose"), default="stiff")
    parser.add_argument("--hands", choices=("virtual", "baxter"), default="virtual")
    parser.add_argument("--models", default="ng,ucm,uacm", help="models (default ng,ucm,uacm)")
    parser.add_argument("--seed", type=int, default=7, help="task seed (default 7)")
    parser.add_argument("--plan-time-limit", type=float, default=10.0,
                        help="wall limit of one planner call [s] (default 10)")
    parser.add_argument("--no-closed", action="store_true", help="skip the re-planning runs")
    parser.add_argument("--carry", choices=("rigid", "projected"), default="rigid",
                        help="how vertical turns move carried links: rigid (the paper, default) "
                             "or projected (cos/cot factors from the state; see docs/encodings.md)")
    parser.add_argument("-o", "--out", type=Path, required=True, help="output folder")


def run(args: argparse.Namespace) -> int:
    from artiplan.execution.fidelity import FidelityConfig, run_fidelity, summarise

    try:
        sizes = tuple(int(s) for s in args.sizes.split(",") if s.strip())
    except ValueError:
        raise UsageError(f"--sizes: expected integers, got {args.sizes!r}") from None
    models = tuple(m.strip().lower() for m in args.models.split(",") if m.strip())
    if not sizes or any(not 3 <= n <= 12 for n in sizes):
        raise UsageError("--sizes: each size must be between 3 and 12")
    if not models or any(m not in ("ng", "ucm", "uacm") for m in models):
        raise UsageError("--models: choose among ng, ucm, uacm")
    if args.tasks < 1:
        raise UsageError("--tasks must be >= 1")
    os.environ.setdefault("MUJOCO_GL", "egl")
    from artiplan.world import make_world

    config = FidelityConfig(tasks=args.tasks, sizes=sizes, preset=args.preset, hands=args.hands,
                            seed=args.seed, models=models, closed_loop=not args.no_closed,
                            plan_time_limit=args.plan_time_limit, carry=args.carry)
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    rows = run_fidelity(config, make_world, progress=lambda s: print(s, flush=True))
    with (out / "runs.jsonl").open("w") as fh:
        for r in rows:
            fh.write(json.dumps(r) + "\n")
    table = summarise(rows)
    write_tables(table, out)
    from artiplan.viz.execution import plot_fidelity

    plot_fidelity(table, out)
    print((out / "fidelity.md").read_text())
    print(f"wrote {out}/runs.jsonl, fidelity.csv, fidelity.md, fidelity-errors.png, "
          "fidelity-success.png")
    return 0


def write_tables(table: list[dict[str, Any]], out: Path) -> None:
    """``fidelity.csv`` and ``fidelity.md`` from the summary rows."""
    with (out / "fidelity.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(table)
    head = ("| preset | links | model | parameters | tasks | planned | RMS err [deg] | "
            "max err [deg] | end err [deg] | goal-link RMS [deg] | goal-link end [deg] | "
            "goal open-loop [%] | success re-planning [%] | re-plans | sim time [s] | wall [s] |")
    lines = [head, "|" + "---|" * len(COLUMNS)]
    for r in table:
        cells = [r[c] for c in COLUMNS]
        lines.append("| " + " | ".join("-" if v is None else str(v) for v in cells) + " |")
    (out / "fidelity.md").write_text("\n".join(lines) + "\n")
