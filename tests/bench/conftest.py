"""A tiny suite for the bench tests: the 3-link NG test problem with a few goal variants."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

DATA = Path(__file__).parents[1] / "backends" / "data"


@pytest.fixture
def tiny_suite(tmp_path: Path) -> Path:
    """``suite.json`` and ``ng/`` with tasks 1..6 of size 3 (each a different goal)."""
    folder = tmp_path / "suite" / "ng"
    folder.mkdir(parents=True)
    shutil.copy(DATA / "ng_domain.pddl", folder / "domain.pddl")
    base = (DATA / "ng3_problem.pddl").read_text()
    entries = []
    for task in range(1, 7):
        text = base.replace("(> (angle l3 z) 120)", f"(> (angle l3 z) {100 + 5 * task})")
        (folder / f"p3-{task}.pddl").write_text(text)
        entries.append({"problem": f"ng/p3-{task}.pddl", "domain": "ng/domain.pddl",
                        "size": 3, "task": task, "model": "ng", "gravity_model": "ng"})
    (tmp_path / "suite" / "suite.json").write_text(json.dumps({"problems": entries}))
    return tmp_path / "suite"
