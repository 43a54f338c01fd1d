"""Read a benchmark suite: ``SUITE_DIR/suite.json`` as written by ``artiplan suite``.

Each problem names its domain and problem files (relative to the suite folder), its gravity model
(``ng``, ``ucm``, ``uacm``), the model's parameter (UCM: gravity speed [deg/s]; UACM: acceleration
[deg/s^2]; NG: none), the object size (number of links) and the task index (random tasks per size).
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from artiplan.errors import InputError

#: Top-level keys that may hold the model parameter, first match wins.
_PARAM_KEYS = ("param", "parameter", "speed_g", "acceleration")


@dataclass(frozen=True)
class SuiteProblem:
    """One problem of the suite. Paths are absolute; ``param`` is None for NG."""

    model: str
    param: float | None
    size: int
    task: int
    domain: str
    problem: str

    @property
    def variant(self) -> str:
        """The model with its parameter, as Table 1's rows name it: ``ng``, ``ucm-0.1``, ..."""
        if self.param is None:
            return self.model
        text = f"{self.param:.1f}" if round(self.param, 1) == self.param else f"{self.param:g}"
        return f"{self.model}-{text}"

    @property
    def problem_id(self) -> str:
        """A short stable name: ``ucm-0.1/size-05/task-2``."""
        return f"{self.variant}/size-{self.size:02d}/task-{self.task}"


def _param(entry: dict[str, Any], model: str) -> float | None:
    if model == "ng":
        return None
    for key in _PARAM_KEYS:
        if entry.get(key) is not None:
            return float(entry[key])
    key = "speed_g" if model == "ucm" else "acceleration"
    for nested in ("parameters", "options"):
        values = entry.get(nested) or {}
        if values.get(key) is not None:
            return float(values[key])
    found = re.search(rf"{model}[-_]([0-9.]+)", str(entry.get("problem", "")))
    return float(found.group(1).rstrip(".")) if found else None


def _entries(data: Any) -> list[dict[str, Any]]:
    if isinstance(data, dict):
        for key in ("problems", "instances", "entries"):
            if isinstance(data.get(key), list):
                return list(data[key])
    if isinstance(data, list):
        return data
    raise ValueError("expected a list of problems, or an object with a 'problems' list")


def load_suite(suite_dir: str | Path) -> list[SuiteProblem]:
    """All problems of the suite in ``suite_dir``, sorted by model, parameter, size, task.

    Raises:
        InputError: no ``suite.json``, or one without the expected fields.
    """
    root = Path(suite_dir)
    index = root / "suite.json"
    if not index.is_file():
        raise InputError(f"{index}: no suite index here (write one with `artiplan suite`)")
    try:
        entries = _entries(json.loads(index.read_text()))
        problems = [_problem(root, entry) for entry in entries]
    except (ValueError, KeyError, TypeError) as exc:
        raise InputError(f"{index}: not a suite index: {exc}") from exc
    return sorted(problems, key=lambda p: (p.model, p.param or 0.0, p.size, p.task))


def _problem(root: Path, entry: dict[str, Any]) -> SuiteProblem:
    # ``artiplan suite`` writes the variant ("ucm-0.1") as model and the model as gravity_model.
    model = str(entry.get("gravity_model") or entry["model"]).lower().split("-")[0]
    size = int(entry.get("size", entry.get("n_links", entry.get("links", 0))))
    task = int(entry.get("task", entry.get("task_index", entry.get("seed", 0))))
    return SuiteProblem(
        model=model, param=_param(entry, model), size=size, task=task,
        domain=str((root / entry["domain"]).resolve()),
        problem=str((root / entry["problem"]).resolve()),
    )


def select(
    problems: Iterable[SuiteProblem],
    models: Iterable[str] | None = None,
    sizes: Iterable[int] | None = None,
) -> list[SuiteProblem]:
    """The problems whose model (``ucm``) or variant (``ucm-0.1``) and size are listed."""
    model_set = {m.lower() for m in models} if models else None
    size_set = set(sizes) if sizes else None
    return [
        p for p in problems
        if (model_set is None or p.model in model_set or p.variant in model_set)
        and (size_set is None or p.size in size_set)
    ]


def on_disk(problems: list[SuiteProblem], suite_dir: str | Path) -> list[SuiteProblem]:
    """The problems whose domain and problem files exist; the missing ones are named on stderr
    (a suite folder copied in part runs what it holds).

    Raises:
        InputError: none of the listed problems is on disk.
    """
    import sys

    present = [p for p in problems if Path(p.domain).is_file() and Path(p.problem).is_file()]
    missing = [p for p in problems if p not in present]
    if missing and not present:
        raise InputError(
            f"{Path(suite_dir) / 'suite.json'}: none of its {len(problems)} problems is on disk "
            f"(first: {missing[0].problem})"
        )
    if missing:
        names = ", ".join(Path(p.problem).relative_to(Path(suite_dir).resolve()).as_posix()
                          if Path(p.problem).is_relative_to(Path(suite_dir).resolve())
                          else p.problem for p in missing[:5])
        more = f" and {len(missing) - 5} more" if len(missing) > 5 else ""
        print(f"artiplan bench: suite.json lists {len(problems)} problems, {len(missing)} are "
              f"missing on disk ({names}{more}): running the {len(present)} present",
              file=sys.stderr)
    return present
