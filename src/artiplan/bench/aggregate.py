"""Numbers behind the reports: Table 1 cells, PAR10, cactus curves, per-problem comparisons.

A run counts as solved only when its row's status is ``solved`` (the plan was valid). Times are
the planner's CPU time [s], as in the paper.
"""

from __future__ import annotations

import math
import statistics
from collections import defaultdict
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Any

Row = dict[str, Any]

#: Table 1's rows in the paper's order (variants of ``artiplan suite``).
VARIANTS: tuple[str, ...] = ("ng", "ucm-0.1", "ucm-0.5", "ucm-1.0", "uacm-0.1", "uacm-0.5")
#: The variants of the paper's PAR10 figure (speed / acceleration 0.1).
PAR10_VARIANTS: tuple[str, ...] = ("ng", "ucm-0.1", "uacm-0.1")
#: PAR10: an unsolved run counts as this many times the time limit.
PENALTY = 10.0


def solved(row: Row) -> bool:
    """Solved with a plan artiplan's validator accepted."""
    return row.get("status") == "solved"


def val_solved(row: Row) -> bool:
    """Solved with a plan stock VAL accepted too."""
    return solved(row) and row.get("val_valid") is True


def has_val(rows: Iterable[Row]) -> bool:
    """True when some row carries stock VAL's verdict."""
    return any(r.get("val_valid") is not None for r in rows)


def latest_rows(rows: Iterable[Row]) -> list[Row]:
    """One row per (planner, problem): the last one recorded."""
    latest: dict[tuple[str, str], Row] = {}
    for row in rows:
        latest[(row["planner"], row["problem"])] = row
    return list(latest.values())


def planners(rows: Iterable[Row]) -> list[str]:
    """Planner names in first-seen order, artiplan first when present."""
    names = list(dict.fromkeys(r["planner"] for r in rows))
    return sorted(names, key=lambda n: (n != "artiplan", names.index(n)))


def sizes(rows: Iterable[Row]) -> list[int]:
    return sorted({int(r["size"]) for r in rows})


def variants(rows: Iterable[Row]) -> list[str]:
    """Variants present, in the paper's order first."""
    present = {r["variant"] for r in rows}
    return [v for v in VARIANTS if v in present] + sorted(present - set(VARIANTS))


def time_limit(rows: Iterable[Row]) -> float:
    """The time limit of the runs [s] (the largest recorded)."""
    return max(float(r.get("time_limit") or 0.0) for r in rows)


@dataclass(frozen=True)
class Cell:
    """One Table 1 cell: ``mean_s`` over solved runs (None if none), ``pct`` solved of ``n``;
    ``val_pct``: solved with a plan stock VAL accepted too (None without VAL's verdicts)."""

    mean_s: float | None
    pct: float
    n: int
    val_pct: float | None = None


def table1(rows: Sequence[Row], planner: str) -> dict[tuple[str, int], Cell]:
    """(variant, size) -> Cell for one planner."""
    groups: dict[tuple[str, int], list[Row]] = defaultdict(list)
    for row in rows:
        if row["planner"] == planner:
            groups[(row["variant"], int(row["size"]))].append(row)
    cells = {}
    with_val = has_val(rows)
    for key, group in groups.items():
        times = [float(r["cpu_s"]) for r in group if solved(r)]
        mean = statistics.fmean(times) if times else None
        val = 100.0 * sum(val_solved(r) for r in group) / len(group) if with_val else None
        cells[key] = Cell(mean, 100.0 * len(times) / len(group), len(group), val)
    return cells


def par10(rows: Sequence[Row], planner: str, limit: float) -> dict[tuple[str, int], float]:
    """(variant, size) -> PAR10 score [s]: mean CPU time, unsolved = 10 x ``limit``."""
    groups: dict[tuple[str, int], list[float]] = defaultdict(list)
    for row in rows:
        if row["planner"] == planner:
            score = float(row["cpu_s"]) if solved(row) else PENALTY * limit
            groups[(row["variant"], int(row["size"]))].append(score)
    return {key: statistics.fmean(values) for key, values in groups.items()}


def cactus(rows: Sequence[Row], planner: str) -> list[float]:
    """Sorted CPU times of the planner's solved runs: the i-th solved problem took times[i]."""
    return sorted(float(r["cpu_s"]) for r in rows if r["planner"] == planner and solved(r))


@dataclass(frozen=True)
class Pair:
    """One problem run by planners ``a`` and ``b``; ratios are a / b (None if undefined)."""

    problem_id: str
    a: Row
    b: Row

    def ratio(self, key: str) -> float | None:
        x, y = self.a.get(key), self.b.get(key)
        if x is None or y is None or not solved(self.a) or not solved(self.b) or y <= 0:
            return None
        return float(x) / float(y)


def pairs(rows: Sequence[Row], a: str, b: str) -> list[Pair]:
    """Problems that both planners ran, in suite order."""
    by_problem: dict[str, dict[str, Row]] = defaultdict(dict)
    for row in rows:
        by_problem[row["problem_id"]][row["planner"]] = row
    found = [Pair(pid, runs[a], runs[b]) for pid, runs in by_problem.items()
             if a in runs and b in runs]
    return sorted(found, key=lambda p: (_variant_rank(p.a["variant"]), p.a["size"], p.a["task"]))


def _variant_rank(variant: str) -> int:
    return VARIANTS.index(variant) if variant in VARIANTS else len(VARIANTS)


@dataclass(frozen=True)
class Summary:
    """Planner ``a`` against ``b`` on the problems both ran.

    ``total_a``/``total_b``: summed CPU time [s] over the problems both solved; ``median_ratio``
    and ``geomean_ratio``: of per-problem CPU time a / b on those problems; ``par10_a``/``_b``:
    PAR10 over all shared problems [s].
    """

    a: str
    b: str
    shared: int
    solved_a: int
    solved_b: int
    both: int
    total_a: float
    total_b: float
    median_ratio: float | None
    geomean_ratio: float | None
    par10_a: float
    par10_b: float


def summarise(rows: Sequence[Row], a: str, b: str, limit: float) -> Summary:
    """Summary of ``a`` versus ``b`` (see :class:`Summary`)."""
    found = pairs(rows, a, b)
    both = [p for p in found if solved(p.a) and solved(p.b)]
    ratios = [max(float(p.a["cpu_s"]), 1e-3) / max(float(p.b["cpu_s"]), 1e-3) for p in both]

    def par(side: str) -> float:
        scores = [
            float(getattr(p, side)["cpu_s"]) if solved(getattr(p, side)) else PENALTY * limit
            for p in found
        ]
        return statistics.fmean(scores) if scores else math.nan

    return Summary(
        a=a, b=b, shared=len(found),
        solved_a=sum(solved(p.a) for p in found), solved_b=sum(solved(p.b) for p in found),
        both=len(both),
        total_a=sum(float(p.a["cpu_s"]) for p in both),
        total_b=sum(float(p.b["cpu_s"]) for p in both),
        median_ratio=statistics.median(ratios) if ratios else None,
        geomean_ratio=math.exp(statistics.fmean(math.log(r) for r in ratios)) if ratios else None,
        par10_a=par("a"), par10_b=par("b"),
    )


def status_counts(rows: Sequence[Row], planner: str) -> dict[str, int]:
    """How many runs of the planner ended in each status."""
    counts: dict[str, int] = defaultdict(int)
    for row in rows:
        if row["planner"] == planner:
            counts[row["status"]] += 1
    return dict(sorted(counts.items()))
