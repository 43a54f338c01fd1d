"""Benchmark results as JSON Lines: one object per finished run, appended and flushed at once.

Reading tolerates a truncated last line (a run killed while writing): it is ignored and the
next append starts on a fresh line, so a restarted benchmark loses nothing and duplicates nothing.
"""

from __future__ import annotations

import json
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

#: Version of the row layout (conventions: every results file carries a ``schema`` field).
SCHEMA = "artiplan-bench/1"


def row_key(planner: str, problem: str) -> tuple[str, str]:
    """Identity of a run: which planner on which problem file (an absolute path)."""
    return planner, problem


def read_rows(path: str | Path) -> list[dict[str, Any]]:
    """Every complete row of a results file (none if it does not exist)."""
    return list(_iter_rows(Path(path)))


def _iter_rows(path: Path) -> Iterator[dict[str, Any]]:
    if not path.is_file():
        return
    with path.open(encoding="utf-8") as handle:
        for line in handle:
            if not line.strip():
                continue
            try:
                row = json.loads(line)
            except json.JSONDecodeError:
                continue  # a line cut short by a kill: that run is simply run again
            if isinstance(row, dict) and "planner" in row and "problem" in row:
                yield row


def done_keys(path: str | Path) -> set[tuple[str, str]]:
    """The (planner, problem) pairs already recorded."""
    return {row_key(row["planner"], row["problem"]) for row in read_rows(path)}


class ResultsWriter:
    """Appends rows to a JSON Lines file; each row is flushed and fsync'ed as it is written."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self._handle = self.path.open("a+", encoding="utf-8")
        self._repair_tail()

    def _repair_tail(self) -> None:
        """Start on a fresh line if the file ends in a partial one (a killed writer)."""
        self._handle.seek(0, os.SEEK_END)
        if self._handle.tell() == 0:
            return
        with self.path.open("rb") as raw:
            raw.seek(-1, os.SEEK_END)
            last = raw.read(1)
        if last != b"\n":
            self._handle.write("\n")
            self._handle.flush()

    def write(self, row: dict[str, Any]) -> None:
        self._handle.write(json.dumps(row, sort_keys=False) + "\n")
        self._handle.flush()
        os.fsync(self._handle.fileno())

    def close(self) -> None:
        self._handle.close()

    def __enter__(self) -> ResultsWriter:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
