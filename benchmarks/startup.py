"""Start-up: wall time of the whole ``artiplan plan`` process on small problems, old against new.

Each run is one fresh process, ``artiplan plan DOMAIN PROBLEM -o OUT -q``, timed from spawn to
exit [s wall]; one process at a time. ``--entry script`` (the default) runs the console script
pip writes for ``artiplan = artiplan.cli:main`` (the process a user's ``artiplan plan`` is),
with this interpreter and each side's tree on PYTHONPATH; ``--entry module`` runs
``python -m artiplan`` instead (``runpy`` and its imports come on top, ~3-5 ms). Each source
tree (``--src``, and ``--old-src``) gets its bytecode compiled first (``python -m compileall``:
the sandbox sets PYTHONDONTWRITEBYTECODE, and a version without cached bytecode would pay for
compiling). The sides alternate within every round (new, old, kairos; then old, kairos, new;
...), so a machine that gets busier or quieter favours none. Kairos (``kairos solve``, the
command line of ``artiplan.backends.kairos``) runs side by side when the backend finds it.

    python benchmarks/startup.py --suite SUITE --old-src /tmp/old/src -n 15 \\
        [--other main=/tmp/main/src] ng/p3-1 ucm-0.5/p3-1 uacm-0.5/p3-1

Prints min / median / max per problem and side, whether the sides' plans are the same, and the
load average before and after (after includes this benchmark's own runs, about 1; a load above
1.5 before the run, from other jobs on this 2-core machine, makes the numbers doubtful: rerun).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

#: The console script pip writes for ``[project.scripts] artiplan = "artiplan.cli:main"``.
CONSOLE_SCRIPT = """import sys
from artiplan.cli import main
if __name__ == '__main__':
    sys.argv[0] = sys.argv[0].removesuffix('.exe')
    sys.exit(main())
"""

HERE = Path(__file__).resolve()
SRC = HERE.parents[1] / "src"
PROBLEMS = ("ng/p3-1", "ucm-0.5/p3-1", "uacm-0.5/p3-1")
MAX_LOAD = 1.5


def load_average() -> float:
    """The 1-minute load average (0 where unknown)."""
    try:
        return os.getloadavg()[0]
    except OSError:
        return 0.0


def kairos_command(src: Path, domain: Path, problem: Path) -> list[str] | None:
    """Kairos's command line as artiplan's backend builds it, or None if kairos is not found."""
    code = ("import json, sys; from pathlib import Path\n"
            "from artiplan.backends.kairos import KairosPlanner\n"
            "from artiplan.errors import ExternalToolError\n"
            "try:\n"
            "    print(json.dumps(KairosPlanner().command(Path(sys.argv[1]), Path(sys.argv[2]),"
            " None, None)))\n"
            "except ExternalToolError:\n"
            "    print('null')\n")
    out = subprocess.run([sys.executable, "-c", code, str(domain), str(problem)],
                         env=dict(os.environ, PYTHONPATH=str(src)), capture_output=True,
                         text=True, check=True).stdout
    found: list[str] | None = json.loads(out)
    return found


def timed(cmd: list[str], env: dict[str, str]) -> tuple[float, int]:
    """Wall seconds of one process run to its end, and its exit code."""
    t = time.perf_counter()
    proc = subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    wall = time.perf_counter() - t
    if proc.returncode != 0:
        sys.stderr.write(proc.stderr.decode(errors="replace")[-2000:])
    return wall, proc.returncode


def read_sides(ap: argparse.ArgumentParser, args: argparse.Namespace) -> dict[str, Path]:
    """The versions to run, label -> src/ (``--src``, ``--old-src``, every ``--other``),
    bytecode-compiled: a tree without it pays for compiling its modules in every process."""
    sides: dict[str, Path] = {"new": args.src.resolve()}
    if args.old_src is not None:
        sides["old"] = args.old_src.resolve()
    for item in args.other:
        label, _, src = item.partition("=")
        if not src or label in sides or label == "kairos":
            ap.error(f"--other wants LABEL=SRC with a new label, got {item!r}")
        sides[label] = Path(src).resolve()
    for src in sides.values():
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(src)], check=True)
    return sides


def problem_files(suite: Path, pid: str) -> tuple[Path, Path]:
    """Domain and problem files of ``FAMILY/NAME`` in a suite folder."""
    family, name = pid.split("/")
    return suite / family / "domain.pddl", suite / family / f"{name}.pddl"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("problems", nargs="*", default=list(PROBLEMS),
                    help="problems as FAMILY/NAME under --suite (default: %(default)s)")
    ap.add_argument("--suite", type=Path, required=True,
                    help="a suite folder (artiplan suite): FAMILY/domain.pddl, FAMILY/NAME.pddl")
    ap.add_argument("--src", type=Path, default=SRC, help="src/ of the new version (this tree)")
    ap.add_argument("--old-src", type=Path, help="src/ of the old version")
    ap.add_argument("--other", action="append", default=[], metavar="LABEL=SRC",
                    help="another version's src/ as a column of its own (repeatable)")
    ap.add_argument("-n", "--runs", type=int, default=15, help="runs per problem and side")
    ap.add_argument("--no-kairos", action="store_true", help="leave Kairos out")
    ap.add_argument("--entry", choices=("script", "module"), default="script",
                    help="how artiplan is started: its console script (default) or python -m")
    ap.add_argument("-o", "--out", type=Path, help="write every run's numbers here (JSON)")
    args = ap.parse_args()

    sides = read_sides(ap, args)
    load_before = load_average()
    if load_before > MAX_LOAD:
        print(f"warning: load average {load_before:.2f} > {MAX_LOAD}: numbers doubtful",
              file=sys.stderr)
    report: dict[str, Any] = {
        "schema": 1, "machine": os.uname().nodename, "cpus": os.cpu_count(),
        "python": sys.version.split()[0], "runs": args.runs,
        "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "sides": {k: str(v) for k, v in sides.items()}, "problems": {},
    }
    report["entry"] = args.entry
    with tempfile.TemporaryDirectory() as tmp:
        script = Path(tmp) / "artiplan"
        script.write_text(CONSOLE_SCRIPT)
        start = [sys.executable, str(script)] if args.entry == "script" else \
            [sys.executable, "-m", "artiplan"]
        for pid in args.problems:
            domain, problem = problem_files(args.suite, pid)
            cmds: dict[str, tuple[list[str], dict[str, str]]] = {}
            for side, src in sides.items():
                out = str(Path(tmp) / f"{side}.plan")
                cmds[side] = ([*start, "plan", str(domain), str(problem), "-o", out, "-q"],
                              dict(os.environ, PYTHONPATH=str(src)))
            kairos = None if args.no_kairos else kairos_command(sides["new"], domain, problem)
            if kairos is not None:
                cmds["kairos"] = (kairos, dict(os.environ))
            elif not args.no_kairos:
                print("note: kairos not found by artiplan.backends.kairos: no Kairos column",
                      file=sys.stderr)
            walls: dict[str, list[float]] = {k: [] for k in cmds}
            order = list(cmds)
            for k in range(args.runs):
                shift = k % len(order)
                for side in order[shift:] + order[:shift]:
                    wall, code = timed(*cmds[side])
                    if code != 0:
                        raise SystemExit(f"{side} on {pid}: exit {code}")
                    walls[side].append(wall)
            plans = {side: (Path(tmp) / f"{side}.plan").read_text() for side in sides}
            report["problems"][pid] = {
                side: {"min": min(w), "median": statistics.median(w), "max": max(w), "walls": w}
                for side, w in walls.items()}
            report["problems"][pid]["same_plan"] = len(set(plans.values())) == 1
    report["load"] = {"before": load_before, "after": load_average()}
    print(f"{report['date']}, {report['machine']} ({report['cpus']} cpus), Python "
          f"{report['python']}, {args.runs} runs a side, entry {args.entry}, load "
          f"{load_before:.2f} -> "
          f"{report['load']['after']:.2f}")
    print("wall [s] min / median / max")
    for pid, row in report["problems"].items():
        cells = [f"{side} {r['min']:.3f} / {r['median']:.3f} / {r['max']:.3f}"
                 for side, r in row.items() if isinstance(r, dict)]
        ratio = (f", old/new median {row['old']['median'] / row['new']['median']:.2f}x"
                 if "old" in row else "")
        same = "" if len(sides) == 1 else f", same plan: {'yes' if row['same_plan'] else 'NO'}"
        print(f"  {pid}: " + "; ".join(cells) + ratio + same)
    if load_before > MAX_LOAD:
        print(f"note: load average {load_before:.2f} > {MAX_LOAD} before the run (other jobs): "
              "numbers doubtful, rerun")
    if args.out:
        args.out.write_text(json.dumps(report, indent=1) + "\n")


if __name__ == "__main__":
    main()
