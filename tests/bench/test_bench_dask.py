"""The Dask path gives the same results as the local pool (apart from timings)."""

from __future__ import annotations

from pathlib import Path

import pytest

from artiplan.bench.jobs import Job
from artiplan.bench.results import read_rows
from artiplan.bench.run import RunConfig, run_jobs
from artiplan.bench.suite import load_suite

COMPARED = ("planner", "problem", "model", "size", "task", "status", "valid", "makespan",
            "n_actions", "plan")


def _jobs(suite: Path) -> list[Job]:
    problems = load_suite(suite)[:3]
    return [Job(name, p, 30.0, 2048.0) for p in problems for name in ("enhsp", "kairos")]


def _comparable(path: Path) -> list[tuple[object, ...]]:
    return sorted(tuple(row[k] for k in COMPARED) for row in read_rows(path))


@pytest.mark.slow
@pytest.mark.ci
@pytest.mark.java
def test_dask_cluster_equals_local_pool(tiny_suite: Path, tmp_path: Path) -> None:
    from distributed import LocalCluster

    jobs = _jobs(tiny_suite)
    local = tmp_path / "local.jsonl"
    assert run_jobs(jobs, local, RunConfig(jobs=2)) == len(jobs)
    remote = tmp_path / "dask.jsonl"
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        written = run_jobs(jobs, remote, RunConfig(scheduler=cluster.scheduler_address))
    assert written == len(jobs)
    assert _comparable(remote) == _comparable(local)
    assert {r["status"] for r in read_rows(remote)} == {"solved"}
