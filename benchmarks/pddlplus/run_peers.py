"""Run ENHSP, Kairos and today's artiplan on the PDDL+ benchmark set; check every plan with VAL.

Usage (from the repository root, one process at a time on a shared machine):
    nice -n 10 .venv/bin/python benchmarks/pddlplus/run_peers.py \\
        [--planners enhsp,kairos,artiplan] [--only FAMILY,...] [--sizes 1,2] [--time-limit 60] \\
        [--out benchmarks/pddlplus/results/peers.jsonl]
    .venv/bin/python benchmarks/pddlplus/run_peers.py --table [--out ...]   # Markdown tables
    .venv/bin/python benchmarks/pddlplus/run_peers.py --second-opinion     # + kairos validate

One JSON line per (planner, problem), appended as soon as the run ends; a rerun skips what the
file already holds (resumable after a kill). Planners:

- ``enhsp``: ENHSP's defaults (WA* with h_add, discretisation delta 1 for planning, execution,
  validation and heuristic), via artiplan's backend (``java -jar enhsp.jar -o D -f P``);
- ``enhsp-sat-hadd``: the same with ``-planner sat-hadd``; ``enhsp-delta0.1``: ``-delta 0.1``;
- ``kairos``: ``kairos solve D P --threads 1 --no-anytime --format ipc --timeout ...``;
- ``artiplan``: the CLI as a user runs it, ``artiplan plan D P --time-limit T -o PLAN -q``.

ENHSP and Kairos run through artiplan's backends (``artiplan.backends``: CPU-time and memory
limits, CPU time of the process tree, plans converted to VAL's format with same-time actions
spread 1 ms apart, as ``artiplan bench`` does). Every plan is checked with stock VAL
(``Validate -t 0.001``) on the real files where VAL reads them, else on the family's VAL twin.
"""

from __future__ import annotations

import argparse
import json
import socket
import sys
import tempfile
from datetime import datetime, timezone
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
sys.path.insert(0, str(HERE))

import valtools  # noqa: E402

SCHEMA = "artiplan.pddlplus-peers/1"
DEFAULT_OUT = HERE / "results" / "peers.jsonl"
MEMORY_MIB = 8192.0


def _planner(name: str) -> Any:
    from artiplan.backends.enhsp import EnhspPlanner
    from artiplan.backends.kairos import KairosPlanner

    if name == "enhsp":
        return EnhspPlanner()
    if name == "enhsp-delta0.1":
        return EnhspPlanner(delta=0.1, name=name)
    if name == "enhsp-sat-hadd":

        class SatHadd(EnhspPlanner):
            def command(self, domain: Path, problem: Path, memory_limit: float | None) -> list[str]:
                return [*super().command(domain, problem, memory_limit), "-planner", "sat-hadd"]

        return SatHadd(name=name)
    if name == "kairos":
        return KairosPlanner()
    raise SystemExit(f"unknown planner {name!r}")


def run_peer(name: str, domain: Path, problem: Path, limit: float) -> dict[str, Any]:
    """ENHSP or Kairos through artiplan's backend: status, times and the plan in VAL's format."""
    from artiplan.semantics.plan_io import format_plan

    result = _planner(name).solve(domain, problem, time_limit=limit, memory_limit=MEMORY_MIB)
    plan = result.plan
    row: dict[str, Any] = {
        "status": result.status.value, "cpu_s": round(result.cpu_s, 3),
        "wall_s": round(result.wall_s, 3), "peak_mb": round(result.peak_mb, 1),
        "returncode": result.returncode, "message": result.message[:400],
        "raw_plan": result.plan_text[:20000],
    }
    if plan is not None:
        row.update(plan=format_plan(plan, events=False), makespan=round(plan.makespan, 6),
                   n_actions=len(plan.actions), plan_end=plan.end)
        if result.extra.get("shifted_actions"):
            row["unshifted_plan"] = format_plan(_unshifted(name, result.plan_text), events=False)
    else:
        lines = [ln.strip() for ln in result.raw_output.splitlines() if ln.strip()]
        row["output_tail"] = "\n".join(lines[-4:])[:1000]
    row.update({k: v for k, v in result.extra.items() if k not in row})
    return row


def _unshifted(name: str, text: str) -> Any:
    """The planner's plan as it wrote it: same-time actions not spread (VAL applies them in
    parallel, so this is usually a mutex violation; recorded to tell timing artefacts apart)."""
    import dataclasses

    from artiplan.semantics.plan_io import parse_enhsp_output, parse_plan

    if name.startswith("enhsp"):
        return parse_enhsp_output("Found Plan:\n" + text)
    plan = parse_plan(text, "<planner output>")
    instant = tuple(dataclasses.replace(a, duration=None) if a.duration == 0 else a
                    for a in plan.actions)
    return dataclasses.replace(plan, actions=instant)


def run_artiplan(domain: Path, problem: Path, limit: float) -> dict[str, Any]:
    """``artiplan plan`` as a user runs it: exit code, last stderr line, the plan it wrote."""
    from artiplan.backends.runner import Limits, run_limited

    with tempfile.TemporaryDirectory(prefix="pddlbench-") as tmp:
        out = Path(tmp) / "plan.txt"
        cmd = [str(ROOT / ".venv" / "bin" / "artiplan"), "plan", str(domain), str(problem),
               "--time-limit", str(limit), "-o", str(out), "-q"]
        # our own limits sit above artiplan's: they catch a run that ignores its limit
        outcome = run_limited(cmd, Limits(time_limit=limit + 15, memory_limit=MEMORY_MIB))
        plan = out.read_text() if out.exists() else None
    lines = [ln for ln in outcome.stderr.strip().splitlines() if ln.strip()]
    errors = [ln for ln in lines if "Error" in ln or "error" in ln]
    status = {0: "solved", 1: "crash", 2: "usage-error", 3: "bad-input", 5: "unsolvable",
              6: "no-plan", 7: "timeout", 8: "memout", 9: "tool-error"}.get(outcome.returncode,
                                                                            "error")
    if outcome.limit_hit:
        status = "timeout" if outcome.limit_hit in ("time", "wall") else "memout"
    row: dict[str, Any] = {
        "status": status, "returncode": outcome.returncode, "cpu_s": round(outcome.cpu_s, 3),
        "wall_s": round(outcome.wall_s, 3), "peak_mb": round(outcome.peak_mb, 1),
        "message": (errors[-1] if errors else (lines[-1] if lines else ""))[:400],
        "stderr_tail": "\n".join(lines[-6:])[:2000],
    }
    if plan is not None and status == "solved":
        row["plan"] = plan
        row["n_actions"] = sum(1 for ln in plan.splitlines() if ln.strip() and ln[0].isdigit())
    return row


def val_check(entry: dict[str, Any], plan: str) -> dict[str, Any]:
    """Stock VAL on a plan: on the real files if VAL reads them, else on the twin, else none."""
    if entry.get("val_reads"):
        dom, prob, on = HERE / entry["domain"], HERE / entry["problem"], "real"
    elif "val_domain" in entry:
        dom, prob, on = HERE / entry["val_domain"], HERE / entry["val_problem"], "twin"
    else:
        return {"val_valid": None, "val_message": "VAL cannot read this family", "val_on": None}
    with tempfile.NamedTemporaryFile("w", suffix=".plan", delete=False) as handle:
        handle.write(plan)
    try:
        verdict = valtools.validate(dom, prob, Path(handle.name))
    finally:
        Path(handle.name).unlink()
    return {"val_valid": verdict.valid, "val_message": verdict.message[:400], "val_on": on}


def second_opinion(out: Path) -> int:
    """Add ``kairos validate``'s verdict (real files) to every row with a plan that lacks one;
    rewrites ``out`` (run it when no run is appending). Returns how many rows were checked."""
    rows = [json.loads(line) for line in out.read_text().splitlines() if line.strip()]
    checked = 0
    for row in rows:
        if not row.get("plan") or "kairos_valid" in row:
            continue
        with tempfile.NamedTemporaryFile("w", suffix=".plan", delete=False) as handle:
            handle.write(row["plan"])
        try:
            dom = HERE / row["problem"].split("/")[0] / "domain.pddl"
            verdict = valtools.kairos_validate(dom, HERE / row["problem"], Path(handle.name))
        finally:
            Path(handle.name).unlink()
        row.update(kairos_valid=verdict.valid, kairos_message=verdict.message[:300])
        checked += 1
    tmp = out.with_suffix(".tmp")
    tmp.write_text("".join(json.dumps(r) + "\n" for r in rows))
    tmp.replace(out)
    return checked


def done_keys(out: Path) -> set[tuple[str, str]]:
    if not out.exists():
        return set()
    keys = set()
    for line in out.read_text().splitlines():
        if line.strip():
            try:
                row = json.loads(line)
            except json.JSONDecodeError:  # a line cut by a kill: rerun that job
                continue
            keys.add((row["planner"], row["problem"]))
    return keys


def run(args: argparse.Namespace) -> int:
    suite = json.loads((HERE / "suite.json").read_text())["problems"]
    if args.only:
        suite = [e for e in suite if e["family"] in set(args.only.split(","))]
    if args.sizes:
        suite = [e for e in suite if e["size"] in {int(s) for s in args.sizes.split(",")}]
    planners = args.planners.split(",")
    done = done_keys(args.out)
    jobs = [(p, e) for e in suite for p in planners if (p, e["problem"]) not in done]
    print(f"{len(jobs)} runs to do ({len(done)} already in {args.out})", file=sys.stderr)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    for k, (planner, entry) in enumerate(jobs, 1):
        dom, prob = HERE / entry["domain"], HERE / entry["problem"]
        if planner == "artiplan":
            row = run_artiplan(dom, prob, args.time_limit)
        else:
            row = run_peer(planner, dom, prob, args.time_limit)
        if row.get("plan"):
            row.update(val_check(entry, row["plan"]))
        if row.get("unshifted_plan"):
            raw = val_check(entry, row["unshifted_plan"])
            row.update(val_unshifted_valid=raw["val_valid"],
                       val_unshifted_message=raw["val_message"])
        row = {"schema": SCHEMA, "planner": planner, "family": entry["family"],
               "size": entry["size"], "problem": entry["problem"], **row,
               "time_limit": args.time_limit, "host": socket.gethostname(),
               "time": datetime.now(timezone.utc).isoformat(timespec="seconds")}
        with args.out.open("a") as out:
            out.write(json.dumps(row) + "\n")
        print(f"[{k}/{len(jobs)}] {planner:9s} {entry['problem']:24s} {row['status']:10s} "
              f"{row['cpu_s']:7.2f} s  VAL: {row.get('val_valid')}  {row.get('message', '')[:60]}",
              file=sys.stderr, flush=True)
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--planners", default="enhsp,kairos,artiplan")
    ap.add_argument("--only", help="comma-separated family names")
    ap.add_argument("--sizes", help="comma-separated sizes (instance numbers)")
    ap.add_argument("--time-limit", type=float, default=60.0, help="CPU-time limit [s]")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT)
    ap.add_argument("--table", action="store_true", help="print the Markdown tables and exit")
    ap.add_argument("--second-opinion", action="store_true",
                    help="add `kairos validate`'s verdict to every plan in --out, then exit")
    args = ap.parse_args(argv)
    if args.second_opinion:
        print(f"{second_opinion(args.out)} plans checked by kairos validate", file=sys.stderr)
        return 0
    if args.table:
        from peers_table import tables

        print(tables(args.out))
        return 0
    return run(args)


if __name__ == "__main__":
    sys.exit(main())
