"""Render the aggregates as Markdown and LaTeX: Table 1 in the paper's layout, comparisons."""

from __future__ import annotations

from collections.abc import Sequence

from artiplan.bench.aggregate import Cell, Pair, Row, Summary, solved

_MODEL_NAMES = {"ng": "NG", "ucm": "UCM", "uacm": "UACM"}


def _split(variant: str) -> tuple[str, str]:
    """``ucm-0.1`` -> (``UCM``, ``0.1``); ``ng`` -> (``NG``, ``""``)."""
    model, _, param = variant.partition("-")
    return _MODEL_NAMES.get(model, model.upper()), param


def cell_text(cell: Cell | None) -> str:
    """The paper's cell: ``mean (percent)``; ``-- (0)`` if none solved; blank without runs.
    With stock VAL's verdicts: ``mean (percent / VAL percent)``."""
    if cell is None:
        return ""
    if cell.mean_s is None:
        mean = "--"
    else:  # the paper's one decimal; two below 1 s so fast planners do not all read 0.0
        mean = f"{cell.mean_s:.1f}" if cell.mean_s >= 1 else f"{cell.mean_s:.2f}"
    if cell.val_pct is None:
        return f"{mean} ({cell.pct:.0f})"
    return f"{mean} ({cell.pct:.0f} / {cell.val_pct:.0f})"


def table1_markdown(
    cells: dict[tuple[str, int], Cell], variants: Sequence[str], sizes: Sequence[int]
) -> str:
    """Table 1 as a Markdown table: rows model + parameter, columns sizes."""
    head = "| Model | Param | " + " | ".join(str(s) for s in sizes) + " |"
    rule = "|---|---|" + "---:|" * len(sizes)
    lines = [head, rule]
    for variant in variants:
        model, param = _split(variant)
        row = [cell_text(cells.get((variant, s))) for s in sizes]
        lines.append(f"| {model} | {param} | " + " | ".join(row) + " |")
    return "\n".join(lines) + "\n"


def table1_latex(
    cells: dict[tuple[str, int], Cell], variants: Sequence[str], sizes: Sequence[int],
    caption: str,
) -> str:
    """Table 1 as LaTeX (the paper's tabular: multirow model names, double rules)."""
    cols = "|".join("c" for _ in sizes)
    lines = [
        r"\begin{table*}[t]", r"\centering", rf"\begin{{tabular}}{{ll|{cols}}}",
        rf" & & \multicolumn{{{len(sizes)}}}{{c}}{{Size}} \\",
        " & & " + " & ".join(str(s) for s in sizes) + r" \\", r"\hline",
    ]
    groups: dict[str, list[str]] = {}
    for variant in variants:
        groups.setdefault(_split(variant)[0], []).append(variant)
    for model, members in groups.items():
        lines.append(r"\hline")
        for i, variant in enumerate(members):
            label = ""
            if i == 0:
                label = (rf"\multirow{{{len(members)}}}{{*}}{{\bf {model}}}" if len(members) > 1
                         else rf"\textbf{{{model}}}")
            cells_text = [cell_text(cells.get((variant, s))) for s in sizes]
            row = f"{label} & {_split(variant)[1]} & " + " & ".join(cells_text) + r" \\"
            lines.append(row)
        lines.append(r"\hline")
    lines += [r"\end{tabular}", rf"\caption{{{caption}}}", r"\end{table*}"]
    return "\n".join(lines) + "\n"


def par10_markdown(
    scores: dict[tuple[str, int], float], variants: Sequence[str], sizes: Sequence[int]
) -> str:
    """PAR10 [s] per variant (rows) and size (columns)."""
    lines = ["| Model | " + " | ".join(str(s) for s in sizes) + " |",
             "|---|" + "---:|" * len(sizes)]
    for variant in variants:
        row = [f"{scores[(variant, s)]:.1f}" if (variant, s) in scores else "" for s in sizes]
        lines.append(f"| {variant} | " + " | ".join(row) + " |")
    return "\n".join(lines) + "\n"


def _num(value: object, digits: int = 2) -> str:
    return "" if value is None else f"{float(value):.{digits}f}"  # type: ignore[arg-type]


def comparison_markdown(found: Sequence[Pair], a: str, b: str) -> str:
    """Per problem: status, CPU time, makespan and actions of both planners, and a / b."""
    head = (
        f"| Problem | {a} | {b} | {a} time [s] | {b} time [s] | time ratio | "
        f"{a} makespan [s] | {b} makespan [s] | makespan ratio | {a} actions | {b} actions | "
        "actions ratio |"
    )
    lines = [head, "|---|---|---|" + "---:|" * 9]
    for pair in found:
        x, y = pair.a, pair.b
        lines.append(
            f"| {pair.problem_id} | {x['status']} | {y['status']} | {_num(x['cpu_s'])} | "
            f"{_num(y['cpu_s'])} | {_num(_time_ratio(pair))} | "
            f"{_num(x['makespan'] if solved(x) else None, 1)} | "
            f"{_num(y['makespan'] if solved(y) else None, 1)} | {_num(pair.ratio('makespan'))} | "
            f"{x['n_actions'] if solved(x) else ''} | {y['n_actions'] if solved(y) else ''} | "
            f"{_num(pair.ratio('n_actions'))} |"
        )
    return "\n".join(lines) + "\n"


def _time_ratio(pair: Pair) -> float | None:
    if not (solved(pair.a) and solved(pair.b)):
        return None
    return max(float(pair.a["cpu_s"]), 1e-3) / max(float(pair.b["cpu_s"]), 1e-3)


def summary_markdown(summaries: Sequence[Summary], limit: float) -> str:
    """One line per planner pair: solved counts, total and median CPU time ratios, PAR10."""
    lines = [
        "| a / b | problems | solved a | solved b | both | total CPU a [s] | total CPU b [s] | "
        "total ratio | median ratio | geo-mean ratio | PAR10 a [s] | PAR10 b [s] |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for s in summaries:
        total_ratio = s.total_a / s.total_b if s.total_b > 0 else None
        lines.append(
            f"| {s.a} / {s.b} | {s.shared} | {s.solved_a} | {s.solved_b} | {s.both} | "
            f"{s.total_a:.1f} | {s.total_b:.1f} | {_num(total_ratio, 3)} | "
            f"{_num(s.median_ratio, 3)} | {_num(s.geomean_ratio, 3)} | {s.par10_a:.1f} | "
            f"{s.par10_b:.1f} |"
        )
    note = (f"\nRatios are a / b of CPU time on the problems both solved; PAR10 counts an "
            f"unsolved run as 10 x {limit:g} s.\n")
    return "\n".join(lines) + "\n" + note


def status_markdown(counts: dict[str, dict[str, int]]) -> str:
    """Runs per planner and final status (solved, invalid, timeout, ...)."""
    names = sorted({s for c in counts.values() for s in c})
    lines = ["| Planner | " + " | ".join(names) + " |", "|---|" + "---:|" * len(names)]
    for planner, c in counts.items():
        lines.append(f"| {planner} | " + " | ".join(str(c.get(n, 0)) for n in names) + " |")
    return "\n".join(lines) + "\n"


def rows_csv(found: Sequence[Row]) -> str:
    """Every run as CSV (no plan text), for spreadsheets."""
    keys = ["planner", "variant", "size", "task", "status", "planner_status", "cpu_s", "wall_s",
            "peak_mb", "makespan", "n_actions", "valid", "val_valid", "problem_id"]
    lines = [",".join(keys)]
    for row in found:
        lines.append(",".join("" if row.get(k) is None else str(row.get(k)) for k in keys))
    return "\n".join(lines) + "\n"


#: The paper's Table 1 (ENHSP, 300 CPU-s, 8 GB, i7-6900K), sizes 3 4 5 6 7 8 10 12, for reference.
PAPER_TABLE1: tuple[tuple[str, str, str], ...] = (
    ("NG", "", "0.4 (100) | 0.6 (100) | 0.7 (80) | 7.3 (80) | 15.5 (40) | 3.8 (20) | 108.4 (60) "
     "| 4.5 (20)"),
    ("UCM", "0.1", "0.5 (100) | 1.9 (100) | 1.3 (80) | 4.4 (60) | 63.9 (40) | 36.0 (20) | -- (0) "
     "| 198.5 (20)"),
    ("UCM", "0.5", "0.5 (100) | 1.9 (100) | 1.3 (80) | 14.9 (80) | 14.5 (40) | 60.7 (20) | -- (0) "
     "| -- (0)"),
    ("UCM", "1.0", "0.5 (100) | 1.7 (100) | 40.0 (80) | 3.2 (80) | 15.4 (40) | 55.3 (20) | -- (0) "
     "| -- (0)"),
    ("UACM", "0.1", "0.5 (100) | 1.2 (100) | 1.3 (80) | 4.4 (60) | 19.3 (20) | 42.5 (20) "
     "| 50.3 (20) | -- (0)"),
    ("UACM", "0.5", "0.5 (100) | 1.2 (100) | 1.3 (80) | 4.8 (60) | 19.4 (20) | 50.0 (20) "
     "| 55.3 (20) | -- (0)"),
)


def paper_table1_markdown() -> str:
    """The paper's Table 1 (ENHSP) as Markdown, to read our tables against."""
    lines = ["| Model | Param | 3 | 4 | 5 | 6 | 7 | 8 | 10 | 12 |",
             "|---|---|" + "---:|" * 8]
    lines += [f"| {model} | {param} | {cells} |" for model, param, cells in PAPER_TABLE1]
    return "\n".join(lines) + "\n"
