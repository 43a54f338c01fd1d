"""Start-up in instructions: the whole ``artiplan plan`` process under ``valgrind
--tool=callgrind``, old against new.

Wall time on these machines drifts by tens of percent within minutes (benchmarks/startup.py
measures it, alternating sides); an instruction count is the same on every run of the same
binary, inputs and environment, whatever else the machine does. It misses what costs time
without instructions (page faults, cache misses, the disk), so it complements the wall times,
it does not replace them. About 20-50x slower than a plain run.

    python benchmarks/startup_instructions.py --suite SUITE --old-src OLD/src \\
        [--other LABEL=SRC ...] [-o out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from startup import CONSOLE_SCRIPT, PROBLEMS, SRC, problem_files, read_sides


def instructions(command: list[str], env: dict[str, str]) -> int:
    """Instructions (callgrind's Ir) of one run of ``command``."""
    with tempfile.TemporaryDirectory() as tmp:
        proc = subprocess.run(["valgrind", "--tool=callgrind",
                               f"--callgrind-out-file={tmp}/cg.out", *command],
                              env=env, capture_output=True, text=True, check=False)
    found = re.search(r"Collected : (\d+)", proc.stderr)
    if proc.returncode != 0 or found is None:
        raise SystemExit(f"valgrind failed ({proc.returncode}): {proc.stderr[-500:]}")
    return int(found.group(1))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("problems", nargs="*", default=list(PROBLEMS),
                    help="FAMILY/NAME under --suite (default: %(default)s)")
    ap.add_argument("--suite", type=Path, required=True, help="a suite folder (artiplan suite)")
    ap.add_argument("--src", type=Path, default=SRC, help="src/ of the new version")
    ap.add_argument("--old-src", type=Path, required=True, help="src/ of the old version")
    ap.add_argument("--other", action="append", default=[], metavar="LABEL=SRC",
                    help="another version's src/ as a column of its own (repeatable)")
    ap.add_argument("-o", "--out", type=Path, help="write the counts here (JSON)")
    args = ap.parse_args()
    if shutil.which("valgrind") is None:
        raise SystemExit("valgrind not found (Debian package valgrind)")
    sides = read_sides(ap, args)
    out: dict[str, object] = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
                              "python": sys.version.split()[0], "problems": {}}
    with tempfile.TemporaryDirectory() as tmp:
        script = Path(tmp) / "artiplan"
        script.write_text(CONSOLE_SCRIPT)
        base = instructions([sys.executable, "-c", "pass"], dict(os.environ))
        out["python_c_pass"] = base
        print(f"python -c pass: {base / 1e6:.1f} M instructions")
        for prob in args.problems:
            domain, problem = problem_files(args.suite, prob)
            counts = {}
            for label, src in sides.items():
                env = dict(os.environ, PYTHONPATH=str(src))
                counts[label] = instructions([sys.executable, str(script), "plan", str(domain),
                                              str(problem), "-q", "-o", f"{tmp}/{label}.plan"],
                                             env)
            out["problems"][prob] = counts  # type: ignore[index]
            cols = ", ".join(f"{k} {v / 1e6:.1f} M" for k, v in counts.items())
            print(f"{prob}: {cols}; old/new {counts['old'] / counts['new']:.2f}x")
    if args.out:
        args.out.write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
