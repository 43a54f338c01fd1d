"""The paper's suite: layout, determinism, shared configurations across models."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from artiplan.cli import main
from artiplan.encoding import SIZES, make_task, write_suite
from artiplan.model import ArticulatedObject, Configuration

MODELS = ["ng", "ucm-0.1", "ucm-0.5", "ucm-1.0", "uacm-0.1", "uacm-0.5"]


@pytest.fixture(scope="module")
def suite_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("suite")
    write_suite(out, seed=0)
    return out


def _files(root: Path) -> dict[str, bytes]:
    return {
        str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()
    }


def test_layout_240_problems_and_6_domains(suite_dir: Path) -> None:
    assert sorted(p.name for p in suite_dir.iterdir()) == sorted([*MODELS, "suite.json"])
    problems = list(suite_dir.glob("*/p*.pddl"))
    assert len(problems) == 240
    assert len(list(suite_dir.glob("*/domain.pddl"))) == 6
    for model in MODELS:
        names = {p.name for p in (suite_dir / model).glob("p*.pddl")}
        assert names == {f"p{n}-{k}.pddl" for n in SIZES for k in range(1, 6)}


def test_byte_identical_across_runs_and_seed_matters(suite_dir: Path, tmp_path: Path) -> None:
    write_suite(tmp_path / "again", seed=0)
    assert _files(tmp_path / "again") == _files(suite_dir)
    write_suite(tmp_path / "other", seed=1)
    assert _files(tmp_path / "other")["ng/p3-1.pddl"] != _files(suite_dir)["ng/p3-1.pddl"]


def _init_angles(text: str) -> list[str]:
    return [line.strip() for line in text.splitlines() if "(= (angle" in line]


def _goal(text: str) -> str:
    return text[text.index("(:goal") :]


def test_same_task_same_configurations_across_models(suite_dir: Path) -> None:
    for n in SIZES:
        for k in range(1, 6):
            texts = [(suite_dir / m / f"p{n}-{k}.pddl").read_text() for m in MODELS]
            assert all(_init_angles(t) == _init_angles(texts[0]) for t in texts)
            assert all(_goal(t) == _goal(texts[0]) for t in texts)


def test_model_parameters_in_problems(suite_dir: Path) -> None:
    assert "(= (speed-g) 0.5)" in (suite_dir / "ucm-0.5" / "p3-1.pddl").read_text()
    assert "(= (speed-g) 1)" in (suite_dir / "ucm-1.0" / "p3-1.pddl").read_text()
    assert "(= (acceleration) 0.5)" in (suite_dir / "uacm-0.5" / "p3-1.pddl").read_text()
    assert "speed-g" not in (suite_dir / "ng" / "p3-1.pddl").read_text()


def test_suite_json_describes_every_problem(suite_dir: Path) -> None:
    index = json.loads((suite_dir / "suite.json").read_text())
    assert index["schema"] == "artiplan.suite/1"
    assert index["seed"] == 0 and index["goal_style"] == "threshold"
    entries = index["problems"]
    assert len(entries) == 240
    assert {e["model"] for e in entries} == set(MODELS)
    for e in entries:
        assert (suite_dir / e["problem"]).is_file() and (suite_dir / e["domain"]).is_file()
        assert len(e["initial"]) == e["size"] == len(e["target"])
        # L1 is clamped: the target keeps it where it is.
        assert e["initial"][0] == e["target"][0]
        text = (suite_dir / e["problem"]).read_text()
        assert e["goal"] and all(cond in text for cond in e["goal"])
    uacm = next(e for e in entries if e["model"] == "uacm-0.5")
    assert uacm["parameters"]["acceleration"] == 0.5 and uacm["gravity_model"] == "uacm"
    task = make_task(uacm["size"], uacm["task"], 0)
    assert [x["theta"] for x in uacm["initial"]] == list(task.initial.theta)
    assert uacm["seed"] == task.seed


def test_tasks_differ_and_are_one_decimal() -> None:
    tasks = [make_task(5, k) for k in range(1, 6)]
    assert len({t.initial for t in tasks}) == 5
    for t in tasks:
        for x in t.initial.theta + t.target.gamma:
            assert 0.0 <= x < 360.0 and round(x, 1) == x


def test_suite_command(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["suite", str(tmp_path / "s"), "--seed", "3", "--goal-style", "window"]) == 0
    assert "240 problems" in capsys.readouterr().out
    text = (tmp_path / "s" / "ng" / "p4-2.pddl").read_text()
    assert "(>= (angle L3" in text and "(> (angle" not in text
    assert main(["suite", str(tmp_path / "t"), "--goal-style", "nope"]) == 2


def test_generate_command(tmp_path: Path) -> None:
    assert main(["generate", "--links", "5", "--model", "uacm", "-o", str(tmp_path / "g")]) == 0
    assert "(define (domain artiplan-uacm)" in (tmp_path / "g" / "domain.pddl").read_text()
    problem = (tmp_path / "g" / "p5.pddl").read_text()
    assert "(:objects L1 L2 L3 L4 L5 - link)" in problem
    assert main(["generate", "--model", "ucm", "--reach-time", "2", "-o", str(tmp_path / "r")]) == 0
    assert "(= (reach-time) 2)" in (tmp_path / "r" / "p4.pddl").read_text()
    assert main(["generate", "--model", "ucm", "--speed-g", "-1", "-o", str(tmp_path)]) == 2
    init, target = tmp_path / "i.json", tmp_path / "t.json"
    obj = ArticulatedObject(3)
    Configuration.hanging(3).save(init, obj)
    Configuration.from_angles([0, 90, 90], [0, 90, 180]).save(target, obj)
    args = ["generate", "--init", str(init), "--target", str(target), "--goal-style", "window"]
    assert main([*args, "--name", "mine", "-o", str(tmp_path / "j")]) == 0
    text = (tmp_path / "j" / "mine.pddl").read_text()
    assert "(= (angle L3 z-axis) 0)" in text and "(>= (angle L3 z-axis) 175)" in text
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    assert main(["generate", "--init", str(bad), "--target", str(bad), "-o", str(tmp_path)]) == 3
    assert main(["generate", "--init", str(bad), "-o", str(tmp_path)]) == 2
