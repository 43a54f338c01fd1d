"""ENHSP (the jar inside PyPI's up-enhsp) parses and searches every generated domain."""

from __future__ import annotations

import importlib.util
import random
import shutil
import subprocess
from pathlib import Path

import pytest

from artiplan.encoding import EncodingOptions, domain_pddl, problem_pddl
from artiplan.encoding.suite import random_pair
from artiplan.model import ArticulatedObject

pytestmark = [pytest.mark.java, pytest.mark.slow, pytest.mark.ci]


def _enhsp_jar() -> Path:
    spec = importlib.util.find_spec("up_enhsp")
    assert spec is not None and spec.submodule_search_locations, "up-enhsp is a dependency"
    jar = Path(next(iter(spec.submodule_search_locations))) / "ENHSP" / "enhsp.jar"
    assert jar.is_file(), f"{jar} missing from the up-enhsp package"
    return jar


@pytest.mark.parametrize(
    "options",
    [
        EncodingOptions("ng"),
        EncodingOptions("ucm", speed_g=0.5),
        EncodingOptions("uacm", acceleration=0.5),
    ],
    ids=["ng", "ucm", "uacm"],
)
def test_enhsp_parses_and_searches(options: EncodingOptions, tmp_path: Path) -> None:
    if shutil.which("java") is None:
        pytest.skip("java is not installed: ENHSP (a Java program) cannot run")
    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(11))
    domain, problem = tmp_path / "domain.pddl", tmp_path / "problem.pddl"
    domain.write_text(domain_pddl(obj, options))
    problem.write_text(problem_pddl(obj, init, target, options, "threshold", seed=11))
    proc = subprocess.run(
        ["java", "-jar", str(_enhsp_jar()), "-o", str(domain), "-f", str(problem)],
        capture_output=True,
        text=True,
        timeout=60,
    )
    out = proc.stdout + proc.stderr
    assert "Domain parsed" in out and "Problem parsed" in out, out[-2000:]
    assert "Exception" not in out, out[-2000:]
    assert "Problem Solved" in out or "unsolvable" in out.lower() or "No plan" in out, out[-2000:]
