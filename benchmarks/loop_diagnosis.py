"""Why closed-loop runs re-plan and fail: per run, from the per-task logs that
``execution_loop.py --logs DIR`` writes (``task-K.json``).

Prints, per run: successes; re-plans by the model in use and their kind (monitor, carry: a
carried link off when its vertical turn stopped, refusal,
goal missed at the final happening); monitor firings by link, what the arms were doing
(turning which pair, or released) and size (small: <= 15 deg); refusals by kind (a static
grasp: every grasp of a link met something at the grasp or on its final leg; the turn; no
arm motion found); dead ends waited out; planned turns by length; runs the physics ended
(MuJoCo diverged).

Usage: .venv/bin/python benchmarks/loop_diagnosis.py NAME=LOGDIR [NAME=LOGDIR ...]
"""

from __future__ import annotations

import collections
import json
import re
import sys
from pathlib import Path
from typing import Any

FIRED = re.compile(r"(L\d+) off the prediction by ([\d.]+)")


def _tasks(root: Path) -> list[dict[str, Any]]:
    paths = sorted(root.glob("task-*.json"), key=lambda p: int(p.stem.split("-")[1]))
    return [json.loads(p.read_text()) for p in paths]


def _kind(reason: str) -> str:
    if reason.startswith("action failed"):
        return "refusal"
    if reason.endswith("when the vertical turn carrying it stopped"):
        return "carry"
    if reason.startswith("goal not reached"):
        return "final"
    return "monitor"


def _doing(log: dict[str, Any], t: float) -> str:
    """What the arms did at time ``t``: the pair turning, or released."""
    done = [h for h in log["happenings"] if h["time"] <= t + 1e-6 and h["ok"]]
    if not done:
        return "-"
    last = done[-1]["action"]
    if last.startswith("(start"):
        return "turning " + " ".join(last.strip("()").split()[1:3])
    return "released" if last.startswith("(stop") else last


def _refusal(did: str) -> str:
    if "no collision-free arm motion" in did:
        return "no arm motion"
    if "at the grasp" in did or "final leg" in did:
        return "static grasp"
    if "turned" in did or "follows the turn" in did:
        return "the turn"
    return "other"


def _turns(plan: dict[str, Any]) -> list[float]:
    """Each planned turn's extent [deg] at 10 deg/s (to the plan's end if never stopped)."""
    acts = plan["actions"]
    end = acts[-1]["time"] if acts else 0.0
    out = []
    for i, a in enumerate(acts):
        if a["action"].startswith("(start"):
            stop = a["action"].replace("start", "stop")
            t = next((b["time"] for b in acts[i + 1:] if b["action"] == stop), end)
            out.append(10.0 * (t - a["time"]))
    return out


def diagnose(name: str, logs: list[dict[str, Any]]) -> None:
    ok = [i + 1 for i, log in enumerate(logs) if log["success"]]
    print(f"## {name}: {len(ok)}/{len(logs)} reached (tasks {ok})")
    replans: collections.Counter[tuple[str, str]] = collections.Counter()
    fired: collections.Counter[tuple[str, str, str]] = collections.Counter()
    refused: collections.Counter[str] = collections.Counter()
    turns: collections.Counter[str] = collections.Counter()
    ended = []
    waits = 0
    for log in logs:
        plans = log["plans"]
        for prev, plan in zip(plans, plans[1:], strict=False):
            replans[(prev["model"], _kind(plan["reason"]))] += 1
            m = FIRED.match(plan["reason"])
            if m:
                size = "small" if float(m.group(2)) <= 15.0 else "big"
                fired[(m.group(1), _doing(log, plan["start_time"]), size)] += 1
        for h in log["happenings"]:
            waits += h["action"] == "(wait)"
            if not h["ok"] and h["action"].startswith("(start"):
                refused[_refusal(h["did"])] += 1
        for plan in plans:
            for deg in _turns(plan):
                turns["< 90" if deg < 90 else "90-180" if deg <= 180 else "> 180"] += 1
        if log["final"].get("error"):
            ended.append(log["final"]["error"])
    print("re-plans and plans after a refusal, by model in use and kind:",
          ", ".join(f"{m} {k} {n}" for (m, k), n in sorted(replans.items())))
    print("monitor firings (link, arms, size):")
    for (link, doing, size), n in fired.most_common():
        print(f"  {n:4d}  {link} {doing} {size}")
    print("refusals:", ", ".join(f"{k} {n}" for k, n in refused.most_common()))
    print("dead ends waited out (hands open for a while):", waits)
    print("planned turns [deg]:", ", ".join(f"{k}: {n}" for k, n in sorted(turns.items())))
    print("runs the physics ended:", len(ended), *ended[:3])


def main() -> None:
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    for arg in sys.argv[1:]:
        name, _, root = arg.partition("=")
        diagnose(name, _tasks(Path(root or name)))
        print()


if __name__ == "__main__":
    main()
