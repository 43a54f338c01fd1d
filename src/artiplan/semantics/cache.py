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
        _MEMO[k] = _MEMO.pop(k)  # most recently used last
        return hit[1]
    if len(_MEMO) >= _MAX_ENTRIES:
        # Dead tasks' entries first, then the least recently used half: a full clear dropped
        # the entry a second view of the same task was about to re-read (a test failed or
        # passed by how many entries the tests before it had left).
        for stale in [k2 for k2, (ref, _) in _MEMO.items() if ref() is None]:
            del _MEMO[stale]
        if len(_MEMO) >= _MAX_ENTRIES:
            for old in list(_MEMO)[: _MAX_ENTRIES // 2]:
                del _MEMO[old]
    value = build()
    _MEMO[k] = (weakref.ref(task), value)
    return value


def cached(task: Task, key: Any) -> Any | None:
    """What :func:`per_task` holds for (task, key), or None; builds nothing."""
    k = (id(task), key)
    hit = _MEMO.get(k)
    if hit is None or hit[0]() is not task:
        return None
    _MEMO[k] = _MEMO.pop(k)
    return hit[1]
