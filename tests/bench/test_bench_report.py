"""Report numbers on hand-made rows: Table 1 cells, PAR10, ratios, and the files written."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from artiplan.bench import aggregate as agg
from artiplan.bench import tables

LIMIT = 10.0


def _row(planner: str, variant: str, size: int, task: int, status: str, cpu: float,
         makespan: float | None = None, actions: int | None = None) -> dict[str, Any]:
    model = variant.split("-")[0]
    return {"planner": planner, "variant": variant, "model": model, "size": size, "task": task,
            "status": status, "cpu_s": cpu, "makespan": makespan, "n_actions": actions,
            "problem": f"/s/{variant}/p{size}-{task}.pddl", "time_limit": LIMIT,
            "problem_id": f"{variant}/size-{size:02d}/task-{task}", "memory_limit": 100,
            "host": "h", "planner_status": status, "wall_s": cpu, "peak_mb": 1, "valid": True}


ROWS = [
    _row("artiplan", "ng", 3, 1, "solved", 1.0, 10.0, 4),
    _row("artiplan", "ng", 3, 2, "solved", 3.0, 12.0, 6),
    _row("artiplan", "ng", 3, 3, "timeout", 10.0),
    _row("artiplan", "ng", 3, 4, "invalid", 0.5, 8.0, 2),  # an invalid plan: not solved
    _row("enhsp", "ng", 3, 1, "solved", 4.0, 20.0, 8),
    _row("enhsp", "ng", 3, 2, "timeout", 10.0),
    _row("enhsp", "ng", 3, 3, "timeout", 10.0),
    _row("enhsp", "ng", 3, 4, "solved", 2.0, 9.0, 3),
    _row("artiplan", "ucm-0.1", 4, 1, "timeout", 10.0),
]


def test_table1_cell_is_mean_of_solved_and_percentage() -> None:
    cells = agg.table1(ROWS, "artiplan")
    assert cells[("ng", 3)] == agg.Cell(2.0, 50.0, 4)
    assert tables.cell_text(cells[("ng", 3)]) == "2.0 (50)"
    assert tables.cell_text(cells[("ucm-0.1", 4)]) == "-- (0)"
    md = tables.table1_markdown(cells, ["ng", "ucm-0.1"], [3, 4])
    assert "| NG |  | 2.0 (50) |  |" in md and "| UCM | 0.1 |  | -- (0) |" in md


def test_par10_counts_unsolved_as_ten_times_the_limit() -> None:
    scores = agg.par10(ROWS, "artiplan", LIMIT)
    assert scores[("ng", 3)] == pytest.approx((1.0 + 3.0 + 100.0 + 100.0) / 4)
    assert scores[("ucm-0.1", 4)] == pytest.approx(100.0)


def test_summary_ratios_on_problems_both_solved() -> None:
    summary = agg.summarise(ROWS, "artiplan", "enhsp", LIMIT)
    assert (summary.shared, summary.solved_a, summary.solved_b, summary.both) == (4, 2, 2, 1)
    assert summary.total_a == 1.0 and summary.total_b == 4.0
    assert summary.median_ratio == pytest.approx(0.25)
    pair = agg.pairs(ROWS, "artiplan", "enhsp")[0]
    assert pair.ratio("makespan") == pytest.approx(0.5) and pair.ratio("n_actions") == 0.5


def test_latex_table_has_the_papers_layout() -> None:
    cells = agg.table1(ROWS, "enhsp")
    tex = tables.table1_latex(cells, ["ng", "ucm-0.1", "ucm-0.5"], [3, 4], "cap")
    assert r"\multicolumn{2}{c}{Size}" in tex and r"\multirow{2}{*}{\bf UCM}" in tex
    assert r"\textbf{NG} &  & 3.0 (50) &  \\" in tex


def test_report_writes_tables_figures_and_index(tmp_path: Path) -> None:
    from artiplan.viz.report import write_report

    written = write_report(ROWS, tmp_path / "report", source="rows")
    names = {p.name for p in written}
    for expected in ("index.md", "table1-artiplan.md", "table1-enhsp.tex", "par10.png",
                     "par10.svg", "cactus.png", "compare-artiplan-vs-enhsp.md", "runs.csv"):
        assert expected in names
    index = (tmp_path / "report" / "index.md").read_text()
    assert "artiplan / enhsp" in index and "![PAR10](par10.png)" in index
    assert (tmp_path / "report" / "par10.png").stat().st_size > 5000


def test_cli_exit_codes_for_bad_input(tmp_path: Path, tiny_suite: Path) -> None:
    from artiplan.cli import main

    assert main(["report", str(tmp_path / "missing.jsonl"), "-o", str(tmp_path / "r")]) == 3
    assert main(["bench", str(tiny_suite), "--planners", "nope", "--out",
                 str(tmp_path / "x.jsonl")]) == 2
    assert main(["bench", str(tmp_path), "--planners", "kairos"]) == 3  # no suite.json
    assert main(["bench", str(tiny_suite), "--sizes", "99", "--out", str(tmp_path / "y")]) == 2


def test_cli_report_from_a_results_file(tmp_path: Path) -> None:
    import json

    from artiplan.cli import main

    results = tmp_path / "results.jsonl"
    results.write_text("".join(json.dumps(r) + "\n" for r in ROWS))
    assert main(["report", str(results), "-o", str(tmp_path / "rep")]) == 0
    table = (tmp_path / "rep" / "table1-enhsp.md").read_text()
    assert "3.0 (50)" in table
