"""A progress bar with an ETA, on stderr.

On a terminal the bar redraws in place; otherwise (a log file, ``nohup``) it prints one line per
finished run, so the log shows every result as it comes.
"""

from __future__ import annotations

import sys
import time
from typing import Any, TextIO


def _clock(seconds: float) -> str:
    seconds = int(max(0, seconds))
    hours, rest = divmod(seconds, 3600)
    return f"{hours}:{rest // 60:02d}:{rest % 60:02d}"


class Progress:
    """Counts finished runs out of ``total``; ``skipped`` were already in the results file."""

    def __init__(self, total: int, skipped: int = 0, stream: TextIO | None = None) -> None:
        self.total = total
        self.skipped = skipped
        self.done = 0
        self.start = time.monotonic()
        self.stream = stream if stream is not None else sys.stderr
        self.tty = self.stream.isatty()

    def line(self, row: dict[str, Any] | None = None) -> str:
        """The current status line (after ``row`` finished, if given)."""
        elapsed = time.monotonic() - self.start
        remaining = self.total - self.done
        eta = elapsed / self.done * remaining if self.done else float("nan")
        width = 24
        filled = int(width * self.done / self.total) if self.total else width
        bar = "#" * filled + "." * (width - filled)
        text = (
            f"[{bar}] {self.done}/{self.total}"
            + (f" (+{self.skipped} done before)" if self.skipped else "")
            + f" elapsed {_clock(elapsed)} ETA "
            + (_clock(eta) if self.done else "?")
        )
        if row is not None:
            text += (
                f" | {row['planner']} {row['problem_id']}: {row['status']}"
                f" {row['cpu_s']:.1f}s"
            )
        return text

    def update(self, row: dict[str, Any]) -> None:
        """One more run finished."""
        self.done += 1
        text = self.line(row)
        if self.tty:
            self.stream.write("\r\x1b[2K" + text[:200])
        else:
            self.stream.write(text + "\n")
        self.stream.flush()

    def close(self) -> None:
        if self.tty:
            self.stream.write("\n")
            self.stream.flush()
