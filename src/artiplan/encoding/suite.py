"""The paper's benchmark suite: 8 sizes x 5 tasks x 6 model settings = 240 problems.

Layout: ``OUTDIR/<model>/domain.pddl``, ``OUTDIR/<model>/p<size>-<task>.pddl`` with ``<model>``
in ``ng ucm-0.1 ucm-0.5 ucm-1.0 uacm-0.1 uacm-0.5``, and ``OUTDIR/suite.json``. Everything
follows from one seed: task ``(size, task)`` draws its initial and target configurations from
``random.Random(task_seed(seed, size, task))``, so the same task has the same configurations in
every model, and two runs write byte-identical files.
"""

from __future__ import annotations

import json
import random
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from artiplan.encoding.domain import domain_pddl
from artiplan.encoding.goals import make_goal
from artiplan.encoding.options import EncodingOptions
from artiplan.encoding.problem import problem_pddl
from artiplan.model import ArticulatedObject, Configuration, random_configuration

SCHEMA_SUITE = "artiplan.suite/1"
SIZES: tuple[int, ...] = (3, 4, 5, 6, 7, 8, 10, 12)
TASKS_PER_SIZE = 5
#: (folder, options) of the six model settings of the paper's Table 1.
SUITE_MODELS: tuple[tuple[str, EncodingOptions], ...] = (
    ("ng", EncodingOptions("ng")),
    ("ucm-0.1", EncodingOptions("ucm", speed_g=0.1)),
    ("ucm-0.5", EncodingOptions("ucm", speed_g=0.5)),
    ("ucm-1.0", EncodingOptions("ucm", speed_g=1.0)),
    ("uacm-0.1", EncodingOptions("uacm", acceleration=0.1)),
    ("uacm-0.5", EncodingOptions("uacm", acceleration=0.5)),
)


@dataclass(frozen=True)
class SuiteTask:
    """One task: an object size and a pair of configurations.

    Attributes:
        size: Number of links.
        task: Task number within the size, 1-based.
        seed: The task's own seed (configurations and goal choice).
        initial: Initial configuration [deg].
        target: Target configuration [deg]; L1 equals the initial L1 (clamped).
    """

    size: int
    task: int
    seed: int
    initial: Configuration
    target: Configuration

    @property
    def name(self) -> str:
        return f"p{self.size}-{self.task}"


def task_seed(seed: int, size: int, task: int) -> int:
    """The seed of task ``task`` of size ``size`` in the suite of seed ``seed``."""
    return seed * 10_000 + size * 100 + task


def random_pair(n_links: int, rng: random.Random) -> tuple[Configuration, Configuration]:
    """An initial and a target configuration drawn in that order from ``rng``.

    The target keeps L1's angles equal to the initial ones: L1 is clamped and never moves.
    """
    initial = random_configuration(n_links, rng)
    target = random_configuration(n_links, rng)
    target = Configuration(
        (initial.theta[0], *target.theta[1:]), (initial.gamma[0], *target.gamma[1:])
    )
    return initial, target


def make_task(size: int, task: int, seed: int = 0) -> SuiteTask:
    """Draw one task's configurations from the task's own seed."""
    s = task_seed(seed, size, task)
    initial, target = random_pair(size, random.Random(s))
    return SuiteTask(size, task, s, initial, target)


def suite_tasks(seed: int = 0) -> list[SuiteTask]:
    """The 40 tasks (8 sizes x 5), smallest size first."""
    return [make_task(n, k, seed) for n in SIZES for k in range(1, TASKS_PER_SIZE + 1)]


def _parameters(options: EncodingOptions) -> dict[str, Any]:
    params: dict[str, Any] = {"speed_i": options.speed_i, "speed_d": options.speed_d}
    if options.model == "ucm":
        params["speed_g"] = options.speed_g
    if options.model == "uacm":
        params["acceleration"] = options.acceleration
    return params


def suite_problem(
    label: str, size: int, task: int, seed: int = 0, goal_style: str = "threshold"
) -> tuple[str, str]:
    """The domain and problem text of one suite problem: model setting ``label`` (``ng``,
    ``ucm-0.1``, ...; see :data:`SUITE_MODELS`), ``size`` links, task ``task`` (1-based)."""
    options = dict(SUITE_MODELS).get(label)
    if options is None:
        raise ValueError(f"unknown suite model {label!r}; valid: "
                         f"{', '.join(lb for lb, _ in SUITE_MODELS)}")
    t = make_task(size, task, seed)
    obj = ArticulatedObject(size)
    goal = make_goal(obj, t.target, goal_style, t.seed, planes=options.planes)
    problem = problem_pddl(obj, t.initial, t.target, options, goal=goal, name=t.name)
    return domain_pddl(None, options), problem


def write_suite(outdir: str | Path, seed: int = 0, goal_style: str = "threshold") -> list[Path]:
    """Write the 240 problems, 6 domains and ``suite.json`` under ``outdir``.

    Args:
        outdir: Output folder (created if missing; existing files are overwritten).
        seed: Suite seed.
        goal_style: ``threshold`` (paper) or ``window``.

    Returns:
        Every path written, ``suite.json`` last.
    """
    out = Path(outdir)
    written: list[Path] = []
    tasks = suite_tasks(seed)
    entries = []
    for label, options in SUITE_MODELS:
        folder = out / label
        folder.mkdir(parents=True, exist_ok=True)
        domain_path = folder / "domain.pddl"
        domain_path.write_text(domain_pddl(None, options))
        written.append(domain_path)
        for t in tasks:
            obj = ArticulatedObject(t.size)
            goal = make_goal(obj, t.target, goal_style, t.seed, planes=options.planes)
            text = problem_pddl(obj, t.initial, t.target, options, goal=goal, name=t.name)
            path = folder / f"{t.name}.pddl"
            path.write_text(text)
            written.append(path)
            entries.append(
                {
                    "problem": f"{label}/{t.name}.pddl",
                    "domain": f"{label}/domain.pddl",
                    "size": t.size,
                    "task": t.task,
                    "seed": t.seed,
                    "model": label,
                    "gravity_model": options.model,
                    "parameters": _parameters(options),
                    "initial": t.initial.to_dict()["links"],
                    "target": t.target.to_dict()["links"],
                    "goal": [part for c in goal.conditions for part in c.pddl_parts()],
                }
            )
    index = {
        "schema": SCHEMA_SUITE,
        "seed": seed,
        "goal_style": goal_style,
        "sizes": list(SIZES),
        "tasks_per_size": TASKS_PER_SIZE,
        "models": [label for label, _ in SUITE_MODELS],
        "problems": entries,
    }
    index_path = out / "suite.json"
    index_path.write_text(json.dumps(index, indent=1) + "\n")
    written.append(index_path)
    return written
