"""The trajectory of a simulated plan: every fluent at every happening and event, queryable at
any time (the execution layer's prediction). CSV format: shared/docs/conventions.md."""

from __future__ import annotations

import bisect
import math

from artiplan.pddl.task import fluent_column
from artiplan.records import dataclass, field
from artiplan.semantics.kernel import Segment
from artiplan.semantics.plan import TimedEvent
from artiplan.semantics.state import State

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from pathlib import Path
    from typing import Literal

    RowKind = Literal["init", "action", "event", "sample"]


@dataclass(frozen=True)
class TrajectoryRow:
    """Values after a happening (``kind`` action), an event, at time 0, or a sample."""

    time: float
    happening: str
    values: tuple[float, ...]
    kind: RowKind = "action"


@dataclass
class Trajectory:
    """A simulated plan.

    Attributes:
        fluents: Fluent names as the task prints them (``(angle L2 z-axis)``).
        rows: Time-ordered rows (init, actions, events, optional samples).
        segments: The flows between critical instants; the last one never ends (it extrapolates
            past the plan's last happening).
        events: The events fired, with exact times.
        final_state: The state after the last happening.
        end: Where the simulation stopped [s] (the plan's end, or later when extended).
    """

    fluents: tuple[str, ...]
    rows: list[TrajectoryRow] = field(default_factory=list)
    segments: list[Segment] = field(default_factory=list)
    events: list[TimedEvent] = field(default_factory=list)
    final_state: State | None = None
    end: float | None = None

    @property
    def exact(self) -> bool:
        """True when every flow was solved exactly (no numeric fallback anywhere)."""
        return all(s.flow.exact for s in self.segments)

    @property
    def columns(self) -> list[str]:
        """CSV header: ``time,happening,<fluent>...`` with fluents as ``angle(L2,z-axis)``."""
        return ["time", "happening", *(fluent_column(f) for f in self.fluents)]

    def fluent_index(self, name: str) -> int:
        """Index of a fluent given as ``(angle L2 z-axis)`` or ``angle(L2,z-axis)``."""
        key = fluent_column(name) if name.strip().startswith("(") else name.strip()
        cols = [c.lower() for c in self.columns[2:]]
        try:
            return cols.index(key.replace(" ", "").lower())
        except ValueError:
            raise KeyError(f"no fluent {name!r} in the trajectory") from None

    def values_at(self, t: float) -> tuple[float, ...]:
        """Every fluent at time ``t`` [s]: after any happening at exactly ``t``; past the end,
        the last flow continues (the prediction of what happens if nothing else is done)."""
        if not self.segments:
            return self.rows[-1].values if self.rows else ()
        starts = [s.t0 for s in self.segments]
        k = bisect.bisect_right(starts, t) - 1
        if k < 0:
            return self.rows[0].values if self.rows else self.segments[0].start
        return self.segments[k].values_at(t)

    def value(self, fluent: str, t: float) -> float:
        """One fluent at time ``t`` [s]."""
        return self.values_at(t)[self.fluent_index(fluent)]

    def column(self, fluent: str) -> list[float]:
        """One fluent's value in every row."""
        i = self.fluent_index(fluent)
        return [r.values[i] for r in self.rows]

    def add_samples(self, sample_dt: float, end: float | None = None) -> None:
        """Insert ``sample`` rows every ``sample_dt`` [s] from 0 to ``end`` (default: the last
        row's time), keeping the rows in time order (samples after happenings at equal times)."""
        if sample_dt <= 0 or not math.isfinite(sample_dt):
            raise ValueError(f"sample step must be positive, got {sample_dt}")
        stop = end if end is not None else (self.rows[-1].time if self.rows else 0.0)
        n = int(math.floor(stop / sample_dt + 1e-9))
        samples = [
            TrajectoryRow(k * sample_dt, "", self.values_at(k * sample_dt), "sample")
            for k in range(n + 1)
        ]
        self.rows = sorted([*self.rows, *samples], key=lambda r: (r.time, r.kind == "sample"))

    def to_csv(self, path: str | Path) -> None:
        """Write the wide CSV (conventions.md); times and values with full precision."""
        import csv  # here: most runs write no CSV

        with open(path, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(self.columns)
            for r in self.rows:
                w.writerow([_num(r.time), r.happening, *(_num(v) for v in r.values)])


def _num(x: float) -> str:
    return "" if math.isnan(x) else repr(round(x, 9) + 0.0)
