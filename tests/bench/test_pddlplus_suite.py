"""The general PDDL+ benchmark set (benchmarks/pddlplus): committed files match the generator,
and ``artiplan bench`` reads its suite.json as it is."""

from __future__ import annotations

import json
import subprocess
import sys
from collections import Counter
from pathlib import Path

from artiplan.bench.suite import load_suite

SUITE = Path(__file__).parents[2] / "benchmarks" / "pddlplus"


def test_bench_reads_the_pddlplus_suite() -> None:
    problems = load_suite(SUITE)
    per_family = Counter(p.model for p in problems)
    assert len(per_family) >= 8
    assert min(per_family.values()) >= 8
    for p in problems:
        assert Path(p.domain).is_file() and Path(p.problem).is_file()
        assert p.param is None  # no gravity parameter is read off these names
    ids = [p.problem_id for p in problems]
    assert len(set(ids)) == len(ids)


def test_every_instance_has_a_reference_plan_and_twins_exist() -> None:
    entries = json.loads((SUITE / "suite.json").read_text())["problems"]
    for entry in entries:
        plan = SUITE / entry["reference_plan"]
        assert plan.is_file(), plan
        assert any(line[:1].isdigit() for line in plan.read_text().splitlines())
        if not entry["val_reads"] and entry["reference_check"] == "val-twin":
            assert (SUITE / entry["val_domain"]).is_file()
            assert (SUITE / entry["val_problem"]).is_file()


def test_generator_reproduces_the_committed_files(tmp_path: Path) -> None:
    subprocess.run([sys.executable, str(SUITE / "generate.py"), "--out", str(tmp_path)],
                   check=True, capture_output=True)
    written = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")
                     if p.is_file() and p.name != "README.md")
    assert len(written) > 200
    for rel in written:
        assert (tmp_path / rel).read_bytes() == (SUITE / rel).read_bytes(), rel
