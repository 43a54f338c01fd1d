"""`artiplan world snapshot` and `artiplan world ontology` write what they promise."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image


def _run(*args: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "MUJOCO_GL": os.environ.get("MUJOCO_GL", "egl")}
    return subprocess.run(
        [sys.executable, "-m", "artiplan", "world", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )


@pytest.mark.slow
@pytest.mark.ci
def test_snapshot_writes_images_and_the_configuration(tmp_path: Path) -> None:
    out = tmp_path / "snap"
    r = _run("snapshot", "--links", "3", "--width", "160", "--height", "120", "-o", str(out))
    assert r.returncode == 0, r.stderr
    for cam in ("overhead", "side", "perspective"):
        for kind in ("rgb", "depth", "segmentation"):
            assert (out / f"{cam}_{kind}.png").exists()
    rgb = np.asarray(Image.open(out / "overhead_rgb.png"))
    assert rgb.shape == (120, 160, 3) and rgb.std() > 5.0  # not a blank frame
    seg = np.asarray(Image.open(out / "side_segmentation.png"))
    assert len({tuple(p) for p in seg.reshape(-1, 3)}) >= 3  # background + several links
    conf = json.loads((out / "configuration.json").read_text())
    assert len(conf["links"]) == 3


def test_snapshot_rejects_a_bad_configuration_file(tmp_path: Path) -> None:
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    r = _run("snapshot", str(bad), "-o", str(tmp_path / "o"))
    assert r.returncode == 3


@pytest.mark.slow
def test_ontology_command_writes_owl_and_pddl(tmp_path: Path) -> None:
    r = _run("ontology", "--links", "4", "--no-reason", "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    assert "(connected L1 L2)" in (tmp_path / "problem.pddl").read_text()
    assert "owl:Ontology" in (tmp_path / "world.owl").read_text()
