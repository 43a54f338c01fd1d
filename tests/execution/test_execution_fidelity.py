"""Fidelity: per-link prediction errors from a log, the summary table, its files; the demo."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from artiplan.execution.fidelity import prediction_errors, summarise
from artiplan.execution.runlog import RunLog, schema_errors


def _log(errors: list[list[float]]) -> RunLog:
    conf = {"theta": [0.0] * 3, "gamma": [0.0] * 3}
    log = RunLog({}, {}, conf, conf, ["L3"])
    log.samples = [{"time": float(k), "plan": 0, "kind": "monitor", "predicted": conf,
                    "perceived": conf, "errors": e} for k, e in enumerate(errors)]
    log.samples.append({**log.samples[-1], "plan": 1, "errors": [0.0, 99.0, 99.0]})
    return log


def test_prediction_errors_per_link_first_plan_only() -> None:
    errs = prediction_errors(_log([[0.0, 3.0, 0.0], [0.0, 4.0, 2.0]]))
    assert errs["rms"] == pytest.approx([math.sqrt(12.5), math.sqrt(2)], abs=1e-3)
    assert errs["max"] == [4.0, 2.0]
    assert errs["end"] == [4.0, 2.0]  # the sample of plan 1 (99 deg) is not counted
    assert prediction_errors(RunLog({}, {}, {}, {}, []))["rms"] is None


def test_summary_groups_and_rates() -> None:
    base = {"preset": "stiff", "size": 4, "model": "ucm", "rms_mean": 2.0, "max": 5.0,
            "end_max": 4.0, "goal_rms": 1.0, "goal_end": 1.5, "replans": 0, "sim_s": 10.0,
            "wall_s": 1.0}
    rows = [
        {**base, "task": 1, "calibration": "paper", "mode": "open", "success": True},
        {**base, "task": 2, "calibration": "paper", "mode": "open", "success": False,
         "rms_mean": 4.0},
        {**base, "task": 1, "calibration": "calibrated", "mode": "closed", "success": True,
         "replans": 2},
    ]
    table = summarise(rows)
    assert [(r["calibration"]) for r in table] == ["paper", "calibrated"]
    paper, cal = table
    assert paper["rms_deg"] == 3.0 and paper["open_goal_pct"] == 50.0
    assert paper["closed_success_pct"] is None
    assert cal["closed_success_pct"] == 100.0 and cal["closed_replans"] == 2.0


@pytest.mark.slow
def test_demo_writes_its_outputs(tmp_path: Path) -> None:
    from artiplan.cli import main

    out = tmp_path / "demo"
    code = main(["demo", "-o", str(out), "--hands", "virtual", "--links", "3",
                 "--intervene", "--no-animation"])
    assert code == 0
    log = json.loads((out / "run-log.json").read_text())
    schema = json.loads((out / "run-log.schema.json").read_text())
    assert schema_errors(log, schema) == []
    assert log["interventions"], "the scripted push happened"
    for name in ("angles.png", "plan-0.txt", "encodings/ucm/domain.pddl",
                 "encodings/initial.png"):
        assert (out / name).stat().st_size > 0
