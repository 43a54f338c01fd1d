"""Run logs validate against their JSON Schema; the validator rejects broken logs; dispatch."""

from __future__ import annotations

import copy
import json
import random
from pathlib import Path
from typing import Any

import pytest

from artiplan.encoding import EncodingOptions
from artiplan.encoding.suite import random_pair
from artiplan.execution import RUN_LOG_SCHEMA, SCHEMA_RUN_LOG, LoopConfig, run_loop, schema_errors
from artiplan.execution.dispatch import ActionFailed, dispatch, plan_steps
from artiplan.execution.runlog import write_schema
from artiplan.model import ArticulatedObject
from artiplan.semantics import Plan, TimedAction


@pytest.fixture(scope="module")
def short_log() -> dict[str, Any]:
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, target = random_pair(3, random.Random(4))
    world = make_world(obj, init, hands="virtual", seed=4)
    cfg = LoopConfig(EncodingOptions("ng"), max_replans=1)
    return run_loop(world, target, cfg, seed=4).to_dict()


def test_run_log_validates(short_log: dict[str, Any], tmp_path: Path) -> None:
    assert short_log["schema"] == SCHEMA_RUN_LOG
    assert schema_errors(short_log, RUN_LOG_SCHEMA) == []
    # Round trip through JSON and the schema file.
    data = json.loads(json.dumps(short_log))
    schema = json.loads(write_schema(tmp_path / "s.json").read_text())
    assert schema_errors(data, schema) == []
    assert short_log["samples"] and short_log["plans"]


def test_validator_rejects_broken_logs(short_log: dict[str, Any]) -> None:
    bad = copy.deepcopy(short_log)
    del bad["final"]
    assert any("missing 'final'" in e for e in schema_errors(bad, RUN_LOG_SCHEMA))
    bad = copy.deepcopy(short_log)
    bad["samples"][0]["errors"] = ["x"]
    assert any("samples[0].errors[0]" in e for e in schema_errors(bad, RUN_LOG_SCHEMA))
    bad = copy.deepcopy(short_log)
    bad["schema"] = "artiplan.run-log/0"
    assert schema_errors(bad, RUN_LOG_SCHEMA)


def test_dispatch_vocabulary() -> None:
    from artiplan.world import make_world

    obj = ArticulatedObject(3)
    init, _ = random_pair(3, random.Random(2))
    world = make_world(obj, init, hands="virtual")
    pred = world.true_configuration()

    def step(name: str, *args: str):  # type: ignore[no-untyped-def]
        return plan_steps(Plan((TimedAction(0.0, name, args),)), obj)[0]

    assert dispatch(world, step("observe"), (10.0, 10.0), pred) == "observe"
    did = dispatch(world, step("start-increase", "l2", "l3", "Z-AXIS"), (10.0, 10.0), pred)
    assert did.startswith("hold L2, rotate L3 on z-axis +10")
    with pytest.raises(ActionFailed):  # not neighbours: the world refuses
        dispatch(world, step("start-increase", "L1", "L3", "z-axis"), (10.0, 10.0), pred)
    with pytest.raises(ActionFailed):
        dispatch(world, step("dance"), (10.0, 10.0), pred)
    assert dispatch(world, step("stop-increase", "L2", "L3", "z-axis"), (10.0, 10.0),
                    pred) == "stop and release"
