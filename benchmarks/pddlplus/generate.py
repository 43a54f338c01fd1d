"""Write artiplan's general PDDL+ benchmark set: every family, its instances, reference plans.

Usage (from the repository root):
    .venv/bin/python benchmarks/pddlplus/generate.py [--out DIR] [--only car_linear,...]

Deterministic: the same files on every run (fixed seeds, no clock). Per family FAMILY it writes
``FAMILY/domain.pddl`` (or ``FAMILY/dNN.pddl`` where each instance has its own domain),
``FAMILY/pNN.pddl`` and a reference plan ``FAMILY/pNN.plan`` (VAL's format); where the real files
use constructs stock VAL cannot read and an equivalent VAL-readable model exists, the twin goes to
``FAMILY/val/`` (same file names). It also writes ``suite.json`` (schema ``artiplan.suite/1``, read
by ``artiplan bench``) and the family table of ``README.md`` (between the ``families`` markers).
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from gen.common import Family, Instance  # noqa: E402

SCHEMA = "artiplan.suite/1"
#: The family modules of gen/, in the README's order.
MODULES = ("car", "generator", "convoys", "intercept", "lander", "thermostat", "rover")


def families() -> list[Family]:
    """Every family, in the README's order."""
    found: list[Family] = []
    for name in MODULES:
        found += importlib.import_module(f"gen.{name}").FAMILIES
    return found


def _write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def write_family(root: Path, family: Family) -> list[dict[str, object]]:
    """Write one family's files; return its suite.json entries."""
    folder = root / family.name
    instances: list[Instance] = family.build()
    entries = []
    if family.domain is not None:
        _write(folder / "domain.pddl", family.domain)
    if family.val_domain is not None:
        _write(folder / "val" / "domain.pddl", family.val_domain)
    for inst in instances:
        stem = f"p{inst.size:02d}"
        domain = "domain.pddl"
        if inst.domain is not None:
            domain = f"d{inst.size:02d}.pddl"
            _write(folder / domain, inst.domain)
        _write(folder / f"{stem}.pddl", inst.problem)
        entry: dict[str, object] = {
            "problem": f"{family.name}/{stem}.pddl",
            "domain": f"{family.name}/{domain}",
            "model": family.name,
            "family": family.name,
            "size": inst.size,
            "task": 1,
            "features": list(family.features),
            "val_reads": family.val_reads,
            "params": inst.params,
        }
        if inst.plan is not None:
            _write(folder / f"{stem}.plan", inst.plan)
            entry["reference_plan"] = f"{family.name}/{stem}.plan"
            entry["reference_check"] = inst.plan_check
        if inst.val_domain is not None:
            _write(folder / "val" / domain, inst.val_domain)
        if inst.val_problem is not None:
            _write(folder / "val" / f"{stem}.pddl", inst.val_problem)
        if inst.val_problem is not None or inst.val_domain is not None:
            entry["val_domain"] = f"{family.name}/val/{domain}"
            entry["val_problem"] = f"{family.name}/val/{stem}.pddl"
        entries.append(entry)
    return entries


def readme_table(fams: list[Family], counts: dict[str, int]) -> str:
    """The README's family lines: name, instance count, what it exercises, VAL status."""
    lines = ["| family | instances | exercises | stock VAL | reference plans checked by |",
             "|---|---:|---|---|---|"]
    for family in fams:
        if family.val_reads and family.val_integrates:
            val, check = "parses and validates it", "VAL"
        elif family.val_reads:
            val, check = "parses it, cannot integrate its dynamics", "the generator's closed form"
        elif family.val_domain is not None:
            val, check = "cannot read it; a VAL twin in `val/`", "VAL on the twin"
        else:
            val, check = "cannot read it; no twin possible", "the generator's closed form"
        lines.append(f"| `{family.name}` | {counts[family.name]} | {family.summary} | {val} "
                     f"| {check} |")
    return "\n".join(lines) + "\n"


def update_readme(root: Path, table: str) -> None:
    readme = root / "README.md"
    start, end = "<!-- families -->\n", "<!-- /families -->\n"
    text = readme.read_text() if readme.exists() else f"# PDDL+ benchmarks\n\n{start}{end}"
    head, _, rest = text.partition(start)
    _, _, tail = rest.partition(end)
    readme.write_text(head + start + table + end + tail)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=HERE, help="output folder (default: %(default)s)")
    ap.add_argument("--only", help="comma-separated family names (suite.json is then partial)")
    args = ap.parse_args(argv)
    fams = families()
    if args.only:
        wanted = set(args.only.split(","))
        fams = [f for f in fams if f.name in wanted]
    entries = []
    for family in fams:
        entries += write_family(args.out, family)
        print(f"{family.name}: {sum(1 for e in entries if e['family'] == family.name)} instances")
    index = {
        "schema": SCHEMA,
        "suite": "pddlplus",
        "generator": "benchmarks/pddlplus/generate.py",
        "families": [{"name": f.name, "summary": f.summary, "features": list(f.features),
                      "val_reads": f.val_reads, "notes": f.notes} for f in fams],
        "problems": entries,
    }
    _write(args.out / "suite.json", json.dumps(index, indent=1) + "\n")
    if not args.only:
        counts = {f.name: sum(1 for e in entries if e["family"] == f.name) for f in fams}
        update_readme(args.out, readme_table(fams, counts))
    return 0


if __name__ == "__main__":
    sys.exit(main())
