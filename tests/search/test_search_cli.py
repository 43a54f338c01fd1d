"""``artiplan plan``: output, plan file, statistics and exit codes."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

from artiplan.cli import main
from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.encoding.suite import random_pair
from artiplan.model import ArticulatedObject
from artiplan.pddl import load_task
from artiplan.semantics import validate
from artiplan.semantics.plan_io import read_plan


def _files(tmp_path: Path, n: int = 4, model: str = "ucm", seed: int = 3) -> tuple[Path, Path]:
    obj = ArticulatedObject(n)
    options = EncodingOptions(model)  # type: ignore[arg-type]
    init, target = random_pair(n, random.Random(seed))
    d, p = tmp_path / "domain.pddl", tmp_path / "problem.pddl"
    d.write_text(domain_pddl(obj, options))
    p.write_text(problem_pddl(obj, init, target, options, "threshold", 3))
    return d, p


def test_plan_writes_a_valid_plan_file_and_stats(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    d, p = _files(tmp_path)
    out, stats, traj = tmp_path / "plan.txt", tmp_path / "stats.json", tmp_path / "traj.csv"
    code = main(["plan", str(d), str(p), "-o", str(out), "--stats", str(stats),
                 "--trajectory", str(traj), "--time-limit", "60"])
    assert code == 0
    printed = capsys.readouterr().out
    assert "(start-" in printed
    task = load_task(d, p)
    assert validate(task, read_plan(out, [e.name for e in task.events])).valid
    doc = json.loads(stats.read_text())
    assert doc["status"] == "solved" and doc["expanded"] >= 1 and doc["schema"] == 1
    assert traj.read_text().startswith("time,happening")


def test_plan_exit_code_for_unsolvable(tmp_path: Path) -> None:
    d, p = _files(tmp_path, 3, "ng")
    p.write_text(p.read_text().replace("(:goal (and", "(:goal (and (> (angle L1 z-axis) 400)"))
    assert main(["plan", str(d), str(p), "-q"]) == 5


def test_plan_exit_code_for_time_limit(tmp_path: Path) -> None:
    d, p = _files(tmp_path, 12, "uacm")
    assert main(["plan", str(d), str(p), "--time-limit", "0.001", "-q"]) == 7


def test_plan_rejects_bad_limits(tmp_path: Path) -> None:
    d, p = _files(tmp_path, 3, "ng")
    assert main(["plan", str(d), str(p), "--time-limit", "-1"]) == 2


def test_a_long_search_shows_progress_and_keeps_its_time_limit(tmp_path: Path) -> None:
    """A 30-link UACM problem does not finish in 6 s: progress lines every few seconds, exit 7,
    and the limit covers the whole process (start-up included) within a loose bound (the
    phases before the search check the limit between them; at load 5 on 2 cores start-up,
    grounding and compiling alone take 4-5 s)."""
    import subprocess
    import sys
    import time

    d, p = _files(tmp_path, 30, "uacm", seed=4)  # no plan within 12 s wall (measured)
    start = time.monotonic()
    proc = subprocess.run([sys.executable, "-m", "artiplan", "plan", str(d), str(p),
                           "--time-limit", "6"], capture_output=True, text=True, timeout=120)
    wall = time.monotonic() - start
    assert proc.returncode == 7, proc.stderr[-500:]
    progress = [ln for ln in proc.stderr.splitlines() if " s attempts=" in ln]
    assert progress and "expanded=" in progress[0], proc.stderr[-500:]
    assert "time limit of 6 s reached" in proc.stderr
    assert wall < 6 + 2.0  # generous: only a stuck limit fails this
