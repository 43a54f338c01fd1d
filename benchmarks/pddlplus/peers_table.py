"""Markdown tables of ``run_peers.py`` results: a summary per family and a table per family.

A cell reads ``1.23 s ok`` (solved, VAL accepts the plan), ``1.23 s VAL-x`` (VAL rejects it),
``1.23 s (no VAL)`` (VAL cannot check this family), or the run's status (``timeout``,
``error``, ``bad-input``, ``crash`` ...). Times are CPU seconds of the planner's process tree.
"""

from __future__ import annotations

import json
import statistics
from collections import defaultdict
from pathlib import Path
from typing import Any

Row = dict[str, Any]


def load(path: Path) -> list[Row]:
    """The rows, the last one per (planner, problem) winning."""
    latest: dict[tuple[str, str], Row] = {}
    for line in path.read_text().splitlines():
        if line.strip():
            try:
                row = json.loads(line)
            except json.JSONDecodeError:
                continue
            latest[(row["planner"], row["problem"])] = row
    return list(latest.values())


def cell(row: Row | None) -> str:
    if row is None:
        return ""
    if row["status"] != "solved":
        status = str(row["status"])
        if row["planner"] == "artiplan" and row.get("returncode") is not None:
            status += f" (exit {row['returncode']})"
        return status
    verdict = {True: "ok", False: "VAL-x", None: "(no VAL)"}[row.get("val_valid")]
    return f"{row['cpu_s']:.2f} s {verdict}"


def _counts(rows: list[Row]) -> str:
    solved = [r for r in rows if r["status"] == "solved"]
    valid = sum(r.get("val_valid") is True for r in solved)
    unchecked = sum(r.get("val_valid") is None for r in solved)
    text = f"{len(solved)}/{len(rows)}"
    if solved:
        text += f", VAL ok {valid}" + (f" (+{unchecked} unchecked)" if unchecked else "")
    return text


def summary(rows: list[Row], planners: list[str], families: list[str]) -> str:
    head = "| family | " + " | ".join(f"{p} solved (VAL ok)" for p in planners) + " |"
    lines = [head, "|---|" + "---|" * len(planners)]
    for fam in families:
        cells = [_counts([r for r in rows if r["family"] == fam and r["planner"] == p])
                 for p in planners]
        lines.append(f"| {fam} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def family_table(rows: list[Row], planners: list[str], family: str) -> str:
    by_size: dict[int, dict[str, Row]] = defaultdict(dict)
    for r in rows:
        if r["family"] == family:
            by_size[int(r["size"])][r["planner"]] = r
    lines = ["| instance | " + " | ".join(planners) + " |", "|---|" + "---|" * len(planners)]
    for size in sorted(by_size):
        lines.append(f"| p{size:02d} | " + " | ".join(cell(by_size[size].get(p))
                                                    for p in planners) + " |")
    solved_times = {p: [r["cpu_s"] for r in rows if r["family"] == family and
                        r["planner"] == p and r["status"] == "solved"] for p in planners}
    med = [f"{statistics.median(t):.2f} s" if t else "-" for t in solved_times.values()]
    lines.append("| median (solved) | " + " | ".join(med) + " |")
    return "\n".join(lines) + "\n"


def tables(path: Path) -> str:
    rows = load(path)
    planners = list(dict.fromkeys(r["planner"] for r in rows))
    families = list(dict.fromkeys(r["family"] for r in rows))
    parts = ["## Summary\n", summary(rows, planners, families)]
    for fam in families:
        parts += [f"\n### {fam}\n", family_table(rows, planners, fam)]
    return "\n".join(parts)
