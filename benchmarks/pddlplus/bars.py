"""Issue 13's bars per family, from ``run_peers.py`` rows: artiplan against the better peer.

A plan counts as solved when the run solved it and no check rejected it: stock VAL where it
reads the family (real files or twin), else ``kairos validate`` (``--second-opinion``), else
the run's own validation (artiplan validates every plan it prints; peers' plans unchecked by
any tool are counted as the peer reports them). Time: CPU seconds of the planner's process.

    python benchmarks/pddlplus/bars.py results/peers.jsonl results/artiplan.jsonl
"""

from __future__ import annotations

import argparse
import statistics
from pathlib import Path
from typing import Any

from peers_table import load

Row = dict[str, Any]
PEERS = ("enhsp", "kairos")


def solved(row: Row | None) -> bool:
    """Solved, and no validator that could check the plan rejected it."""
    if row is None or row["status"] != "solved":
        return False
    if row.get("val_valid") is not None:
        return bool(row["val_valid"])
    return row.get("kairos_valid") is not False


def table(rows: list[Row]) -> str:
    """One Markdown line per family: counts, the bar, exits 1, and the common-instance medians."""
    by: dict[tuple[str, str], dict[int, Row]] = {}
    for r in rows:
        by.setdefault((r["family"], r["planner"]), {})[int(r["size"])] = r
    families = list(dict.fromkeys(r["family"] for r in rows))
    lines = ["| family | ENHSP | Kairos | artiplan | bar (>= better peer) | exit 1 | median CPU "
             "on instances all three solve (artiplan / faster peer) |",
             "|---|---:|---:|---:|---|---:|---|"]
    totals = {"enhsp": 0, "kairos": 0, "artiplan": 0}
    for fam in families:
        runs = {p: by.get((fam, p), {}) for p in (*PEERS, "artiplan")}
        counts = {p: sum(solved(r) for r in runs[p].values()) for p in runs}
        for p, n in counts.items():
            totals[p] += n
        best = max(counts[p] for p in PEERS)
        crashes = sum(r.get("returncode") == 1 for r in runs["artiplan"].values())
        common = [s for s in runs["artiplan"] if all(solved(runs[p].get(s))
                                                     for p in runs)]
        if common:
            med = {p: statistics.median(runs[p][s]["cpu_s"] for s in common) for p in runs}
            peer = min(med[p] for p in PEERS)
            speed = f"{med['artiplan']:.2f} s / {peer:.2f} s ({len(common)} instances)"
        else:
            speed = "no instance solved by all three"
        bar = "met" if counts["artiplan"] >= best else f"**not met** ({best - counts['artiplan']}" \
            " short)"
        lines.append(f"| {fam} | {counts['enhsp']} | {counts['kairos']} | {counts['artiplan']} | "
                     f"{bar} | {crashes} | {speed} |")
    lines.append(f"| **total** | {totals['enhsp']} | {totals['kairos']} | {totals['artiplan']} "
                 f"| | | {pooled(by, families)} |")
    return "\n".join(lines) + "\n"


def pooled(by: dict[tuple[str, str], dict[int, Row]], families: list[str]) -> str:
    """The time bar read over all families at once: median CPU of each planner over every
    instance all three solve, artiplan against the peer whose median is lower."""
    cpu: dict[str, list[float]] = {p: [] for p in (*PEERS, "artiplan")}
    for fam in families:
        runs = {p: by.get((fam, p), {}) for p in cpu}
        for s in runs["artiplan"]:
            if all(solved(runs[p].get(s)) for p in runs):
                for p in cpu:
                    cpu[p].append(runs[p][s]["cpu_s"])
    if not cpu["artiplan"]:
        return "no instance solved by all three"
    med = {p: statistics.median(v) for p, v in cpu.items()}
    peer = min(PEERS, key=lambda p: med[p])
    return (f"all families pooled: {med['artiplan']:.2f} s / {med[peer]:.2f} s ({peer}; "
            f"{len(cpu['artiplan'])} instances)")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="+", type=Path, help="run_peers.py JSONL files (later win)")
    args = ap.parse_args(argv)
    rows: dict[tuple[str, str], Row] = {}
    for f in args.files:
        for r in load(f):
            rows[(r["planner"], r["problem"])] = r
    print(table(list(rows.values())))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
