"""Run many jobs, locally or on a Dask cluster, writing each row the moment it finishes.

Both paths submit the same :func:`~artiplan.bench.jobs.run_job`. Locally, ``jobs`` threads each
wait on one planner process (the work happens in the child processes, so threads suffice, and a
thread that dies takes its planner with it). With a scheduler address, the jobs go to a
``dask.distributed`` cluster whose workers must have artiplan installed; one job per worker
thread (start workers with ``--nthreads 1`` so runs do not share a core).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ThreadPoolExecutor, wait
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from artiplan.bench.jobs import Job, run_job
from artiplan.bench.progress import Progress
from artiplan.bench.results import ResultsWriter, done_keys, row_key

Row = dict[str, Any]


@dataclass(frozen=True)
class RunConfig:
    """How to run: ``jobs`` local workers, or a Dask ``scheduler`` address (``tcp://host:port``)."""

    jobs: int = 1
    scheduler: str | None = None


def pending_jobs(jobs: Iterable[Job], out: str | Path) -> tuple[list[Job], int]:
    """The jobs not yet recorded in ``out``, and how many were skipped."""
    done = done_keys(out)
    all_jobs = list(jobs)
    todo = [j for j in all_jobs if row_key(j.planner, j.problem.problem) not in done]
    return todo, len(all_jobs) - len(todo)


def run_jobs(
    jobs: list[Job],
    out: str | Path,
    config: RunConfig,
    on_row: Callable[[Row], None] | None = None,
) -> int:
    """Run the jobs not yet in ``out``; append each row as it ends. Returns rows written."""
    todo, skipped = pending_jobs(jobs, out)
    progress = Progress(len(todo), skipped)
    source = _dask_rows(todo, config.scheduler) if config.scheduler else _local_rows(todo, config)
    written = 0
    with ResultsWriter(out) as writer:
        try:
            for row in source:
                writer.write(row)
                written += 1
                progress.update(row)
                if on_row is not None:
                    on_row(row)
        finally:
            progress.close()
    return written


def _local_rows(todo: list[Job], config: RunConfig) -> Iterator[Row]:
    """Rows as the local pool finishes them (at most ``jobs`` planners at once)."""
    queue = iter(todo)
    with ThreadPoolExecutor(max_workers=max(1, config.jobs)) as pool:
        running: set[Future[Row]] = set()
        for job in queue:
            running.add(pool.submit(run_job, job))
            if len(running) >= max(1, config.jobs):
                break
        while running:
            finished, running = wait(running, return_when=FIRST_COMPLETED)
            for future in finished:
                yield future.result()
                following = next(queue, None)
                if following is not None:
                    running.add(pool.submit(run_job, following))


def _dask_rows(todo: list[Job], address: str) -> Iterator[Row]:
    """Rows as the Dask cluster at ``address`` finishes them."""
    from distributed import Client, as_completed

    from artiplan.errors import ExternalToolError

    try:
        client = Client(address, timeout="20s")
    except OSError as exc:
        raise ExternalToolError(f"cannot reach the Dask scheduler at {address}: {exc}") from exc
    try:
        futures = [
            client.submit(run_job, job, pure=False) for job in todo
        ]
        for future in as_completed(futures):
            yield future.result()
            future.release()
    finally:
        client.close()
