"""Markdown tables of ``run_peers.py`` results: a summary per family and a table per family.

A cell reads ``1.23 s ok`` (solved, VAL accepts the plan), ``1.23 s VAL-x`` (VAL rejects it);
where VAL cannot check the family, ``kv-ok`` / ``kv-x`` is the verdict of ``kairos validate``
(``run_peers.py --second-opinion``); otherwise the run's status (``timeout``, ``error``,
``bad-input``, ``crash`` ...). Times are CPU seconds of the planner's process tree.
"""

from __future__ import annotations

import json
import re
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
    verdict = {True: "ok", False: "VAL-x", None: ""}[row.get("val_valid")]
    if row.get("val_valid") is None:  # VAL cannot check this family: Kairos's validator
        verdict = {True: "kv-ok", False: "kv-x", None: "(unchecked)"}[row.get("kairos_valid")]
    return f"{row['cpu_s']:.2f} s {verdict}"


def _counts(rows: list[Row]) -> str:
    solved = [r for r in rows if r["status"] == "solved"]
    valid = sum(r.get("val_valid") is True for r in solved)
    unchecked = sum(r.get("val_valid") is None for r in solved)
    text = f"{len(solved)}/{len(rows)}"
    if solved and unchecked < len(solved):
        text += f", VAL ok {valid}"
    if unchecked:
        kv = sum(r.get("kairos_valid") is True for r in solved if r.get("val_valid") is None)
        text += f", kairos-validate ok {kv} of {unchecked} VAL cannot check"
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


def reason(row: Row) -> str:
    """The gist of a failed run: the exception, or artiplan's ``error:`` message, shortened."""
    text = str(row.get("stderr_tail") or row.get("output_tail") or row.get("message") or "")
    exc = re.findall(r"^\s*(\w+(?:Error|Exception)): (.*)$", text, re.M)
    if exc:
        name, msg = exc[-1]
        return f"{name}: {msg}"[:110]
    found = re.search(r"error: \S+?:(\d+):(\d+): (.*)", text)
    if found:
        return f"{found.group(3)}"[:110]
    return str(row.get("message", ""))[:110]


def before_picture(rows: list[Row], families: list[str], planner: str = "artiplan") -> str:
    """Per family: how today's ``planner`` ends on its instances, with the typical message."""
    lines = [f"| family | {planner}: outcomes | message |", "|---|---|---|"]
    for fam in families:
        mine = [r for r in rows if r["family"] == fam and r["planner"] == planner]
        if not mine:
            continue
        counts: dict[str, int] = defaultdict(int)
        for r in mine:
            code = r.get("returncode")
            counts[f"{r['status']} (exit {code})" if code is not None else r["status"]] += 1
        failed = [reason(r) for r in mine if r["status"] != "solved"]
        common = max(set(failed), key=failed.count) if failed else ""
        outcome = ", ".join(f"{n} {k}" for k, n in sorted(counts.items()))
        lines.append(f"| {fam} | {outcome} | {common.replace('|', '/')} |")
    return "\n".join(lines) + "\n"


def tables(path: Path) -> str:
    rows = load(path)
    planners = list(dict.fromkeys(r["planner"] for r in rows))
    families = list(dict.fromkeys(r["family"] for r in rows))
    parts = ["## Summary\n", summary(rows, planners, families)]
    if "artiplan" in planners:
        parts += ["\n## Today's artiplan (before)\n", before_picture(rows, families)]
    for fam in families:
        parts += [f"\n### {fam}\n", family_table(rows, planners, fam)]
    return "\n".join(parts)
