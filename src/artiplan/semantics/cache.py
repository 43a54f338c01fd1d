"""Per-task caches of compiled conditions (compiling is slow; tasks are immutable)."""

from __future__ import annotations

import weakref
from collections.abc import Callable

from artiplan.pddl.task import Task

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from typing import Any, TypeVar

    T = TypeVar("T")

# Not a setting: a memo keyed by the task's identity, holding only a weak reference to it.
_MEMO: dict[tuple[int, Any], tuple[weakref.ref[Task], Any]] = {}
_MAX_ENTRIES = 256


def per_task(task: Task, key: Any, build: Callable[[], T]) -> T:
    """``build()`` computed once per (task, key) while the task lives."""
    k = (id(task), key)
    hit = _MEMO.get(k)
    if hit is not None and hit[0]() is task:
        return hit[1]
    if len(_MEMO) >= _MAX_ENTRIES:
        _MEMO.clear()
    value = build()
    _MEMO[k] = (weakref.ref(task), value)
    return value


def cached(task: Task, key: Any) -> Any | None:
    """What :func:`per_task` holds for (task, key), or None; builds nothing."""
    hit = _MEMO.get((id(task), key))
    return hit[1] if hit is not None and hit[0]() is task else None
