"""Time and memory limits, checked from inside the search loop.

Time: wall clock and process CPU time, both against the same limit [s]. Memory: the resident set
size growth since the search started [MB], read with ``psutil`` every ``every`` checks (a cheap
call, but not free); a ``MemoryError`` raised by Python anywhere is reported the same way.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable

from artiplan.records import dataclass, field


class LimitReached(Exception):
    """The search ran out of time (``kind == 'time'``) or memory (``'memory'``)."""

    def __init__(self, kind: str, detail: str) -> None:
        super().__init__(detail)
        self.kind = kind


def rss_mb() -> float:
    """Resident set size of this process [MB] (Linux ``/proc``; psutil elsewhere, imported only
    then: it costs a sizeable part of a small problem's start-up)."""
    try:
        with open("/proc/self/statm") as fh:
            return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20
    except OSError:  # pragma: no cover - not Linux
        import psutil

        return float(psutil.Process(os.getpid()).memory_info().rss) / 2**20


@dataclass
class Limits:
    """Limits of one planning call; ``check()`` raises :class:`LimitReached`.

    ``on_progress(elapsed)`` is called from ``check()`` at most every ``progress_every``
    seconds [s] of wall time (a long search shows it is alive).
    """

    time_limit: float | None = None
    memory_limit: float | None = None  # MB
    every: int = 128
    on_progress: Callable[[float], None] | None = None
    progress_every: float = 2.0
    _wall0: float = field(default_factory=time.monotonic)
    _cpu0: float = field(default_factory=time.process_time)
    _rss0: float = 0.0
    _calls: int = 0
    _reported: float = 0.0

    def __post_init__(self) -> None:
        if self.memory_limit is not None:
            self._rss0 = rss_mb()

    def elapsed(self) -> float:
        """Wall-clock seconds since the limits started."""
        return time.monotonic() - self._wall0

    def remaining(self) -> float | None:
        return None if self.time_limit is None else self.time_limit - self.elapsed()

    def check(self) -> None:
        self._calls += 1
        if self.on_progress is not None:
            now = time.monotonic() - self._wall0
            if now - self._reported >= self.progress_every:
                self._reported = now
                self.on_progress(now)
        if self.time_limit is not None:
            wall = time.monotonic() - self._wall0
            # process_time() is a system call that can cost milliseconds on a VM: read it less
            # often (the CPU time never runs ahead of the wall clock in one thread)
            cpu = time.process_time() - self._cpu0 if self._calls % 16 == 0 else 0.0
            if wall > self.time_limit or cpu > self.time_limit:
                cpu = time.process_time() - self._cpu0
                raise LimitReached(
                    "time", f"time limit of {self.time_limit:g} s reached "
                    f"(wall {wall:.2f} s, cpu {cpu:.2f} s)")
        if self.memory_limit is not None and self._calls % self.every == 0:
            used = rss_mb() - self._rss0
            if used > self.memory_limit:
                raise LimitReached(
                    "memory", f"memory limit of {self.memory_limit:g} MB reached "
                    f"(search grew by {used:.0f} MB)")
