"""Shared pieces of the PDDL+ benchmark generator: instances, number and plan formatting.

Every family module exposes ``FAMILIES``: a list of :class:`Family`, each with a ``build()`` that
returns its instances. Nothing here touches the disk; ``generate.py`` writes the files.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

#: Separation of actions meant one after the other [s]: 10x VAL's tolerance (-t 0.001).
GAP = 0.01


def num(value: float, digits: int = 6) -> str:
    """A number as PDDL text: at most ``digits`` decimals, no trailing zeros, no ``-0``."""
    text = f"{value:.{digits}f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


@dataclass(frozen=True)
class Step:
    """One plan line: an action at ``time`` [s], with a duration [s] for durative actions."""

    time: float
    action: str
    duration: float | None = None


def plan_text(steps: Sequence[Step], header: str = "") -> str:
    """A plan in VAL's format: ``t: (action) [d]``, times with 6 decimals, sorted by time."""
    lines = [f"; {line}" for line in header.splitlines()] if header else []
    for step in sorted(steps, key=lambda s: s.time):
        line = f"{step.time:.6f}: ({step.action})"
        if step.duration is not None:
            line += f" [{step.duration:.6f}]"
        lines.append(line)
    return "\n".join(lines) + "\n"


@dataclass
class Instance:
    """One problem of a family.

    ``size`` is the instance's index of difficulty (1 = easiest); ``params`` the knobs it was
    built from (recorded in suite.json). ``plan`` is a reference plan known to be valid (checked
    by VAL where VAL reads the domain, else by ``plan_check``). ``val_domain``/``val_problem``
    are VAL-readable twins (same actions, same trajectories) where the real files use constructs
    VAL cannot read; None where the real files are VAL-readable (or no twin exists).
    """

    size: int
    problem: str
    plan: str | None
    params: dict[str, object] = field(default_factory=dict)
    domain: str | None = None  # a per-instance domain; None = the family's domain
    val_domain: str | None = None
    val_problem: str | None = None
    plan_check: str = "val"  # "val", "val-twin" or the generator's own simulation ("sim")


@dataclass(frozen=True)
class Family:
    """A benchmark family: one domain (or one per instance), instances of growing difficulty."""

    name: str
    summary: str  # one README line: what it exercises
    features: tuple[str, ...]
    domain: str | None
    build: Callable[[], list[Instance]]
    val_reads: bool = True  # stock VAL parses the real domain
    val_integrates: bool = True  # ... and integrates its dynamics (else: no VAL verdict)
    val_domain: str | None = None  # VAL twin of the family's domain (see Instance)
    notes: str = ""


def bisect(f: Callable[[float], float], lo: float, hi: float, iters: int = 100) -> float:
    """A root of ``f`` in [lo, hi] by bisection; ``f(lo)`` and ``f(hi)`` must differ in sign."""
    flo = f(lo)
    if flo == 0:
        return lo
    if (flo > 0) == (f(hi) > 0):
        raise ValueError(f"no sign change on [{lo}, {hi}]")
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if fm == 0:
            return mid
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)
