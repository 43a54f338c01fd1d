"""A benchmark killed mid-way and restarted with the same --out loses and repeats nothing."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import pytest

from artiplan.bench.results import read_rows


def _bench(suite: Path, out: Path) -> list[str]:
    return [sys.executable, "-m", "artiplan", "bench", str(suite), "--planners", "enhsp",
            "--time-limit", "30", "--memory-limit", "2048", "--jobs", "1", "--out", str(out)]


@pytest.mark.slow
@pytest.mark.ci
@pytest.mark.java
def test_resume_after_kill(tiny_suite: Path, tmp_path: Path) -> None:
    out = tmp_path / "results.jsonl"
    first = subprocess.Popen(_bench(tiny_suite, out), stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while len(read_rows(out)) < 2 and time.monotonic() < deadline and first.poll() is None:
        time.sleep(0.05)
    os.kill(first.pid, signal.SIGKILL)  # no chance to clean up
    first.wait()
    before = read_rows(out)
    assert 2 <= len(before) < 6, "kill the run mid-way"
    with out.open("a") as handle:
        handle.write('{"planner": "enhsp", "problem": "/cut')  # as if killed mid-write
    second = subprocess.run(_bench(tiny_suite, out), capture_output=True, text=True, timeout=120)
    assert second.returncode == 0, second.stderr[-1000:]
    rows = read_rows(out)
    keys = Counter((r["planner"], r["problem"]) for r in rows)
    assert len(keys) == 6 and set(keys.values()) == {1}  # all six, none twice
    assert rows[: len(before)] == before  # the first run's rows are kept as they were
    assert all(r["status"] == "solved" for r in rows)
    assert "(+" in second.stderr  # the progress line reports the runs done before
