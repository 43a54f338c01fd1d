"""Process CPU of ``artiplan plan`` on a few instances, several src trees alternating.

Usage (from the repository root, one heavy job at a time on a shared machine):
    nice -n 5 .venv/bin/python benchmarks/pddlplus/cpu_old_new.py --rounds 3 --out OUT.jsonl \\
        --src old=/path/old/src --src new=/path/new/src intercept/p01 intercept/p03 convoys/p01

Each run is ``python -m artiplan plan D P -o PLAN -q`` with PYTHONPATH = that src, timed as
run_peers.py times every planner: CPU (user + sys) of the child process. The order of the
trees alternates round by round. One JSON line per run (the plan text included); the last
lines printed are the median CPU per (instance, tree). Whether a tree has compiled bytecode
(``python -m compileall SRC``) is part of what is measured: this machine sets
PYTHONDONTWRITEBYTECODE, so a tree without ``__pycache__`` compiles every module each run.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("problems", nargs="+", help="FAMILY/pNN of benchmarks/pddlplus")
    ap.add_argument("--src", action="append", required=True, help="NAME=PATH of a src/ tree")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--out", type=Path, required=True)
    args = ap.parse_args()
    trees = dict(s.split("=", 1) for s in args.src)
    cpu: dict[tuple[str, str], list[float]] = {}
    with args.out.open("w") as out, tempfile.TemporaryDirectory() as tmp:
        for r in range(args.rounds):
            for prob in args.problems:
                fam, name = prob.split("/")
                order = list(trees) if r % 2 == 0 else list(trees)[::-1]
                for tree in order:
                    plan = Path(tmp) / f"{tree}.plan"
                    env = dict(os.environ, PYTHONPATH=trees[tree])
                    before = resource.getrusage(resource.RUSAGE_CHILDREN)
                    t = time.monotonic()
                    proc = subprocess.run(
                        [sys.executable, "-m", "artiplan", "plan", str(HERE / fam / "domain.pddl"),
                         str(HERE / fam / f"{name}.pddl"), "-o", str(plan), "-q"],
                        env=env, capture_output=True, text=True)
                    wall = time.monotonic() - t
                    after = resource.getrusage(resource.RUSAGE_CHILDREN)
                    used = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
                    cpu.setdefault((prob, tree), []).append(used)
                    row = {"round": r, "tree": tree, "problem": prob, "rc": proc.returncode,
                           "cpu_s": round(used, 3), "wall_s": round(wall, 3),
                           "load": os.getloadavg()[0],
                           "plan": plan.read_text() if plan.exists() else None}
                    print(json.dumps(row), file=out, flush=True)
    for (prob, tree), values in sorted(cpu.items()):
        print(f"{prob:16s} {tree:12s} median CPU {statistics.median(values):.3f} s  "
              f"({', '.join(f'{v:.3f}' for v in values)})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
