"""The layer contract of docs/design/interfaces.md: each stage imports only stages above it.

Checked statically on the source (ast), so a forbidden import fails here even if it is never
executed by another test.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src" / "artiplan"

#: Pipeline order: a package may import itself and packages before it, never after.
LAYERS = [
    "model",
    "encoding",
    "pddl",
    "semantics",
    "search",
    "backends",
    "up",
    "world",
    "execution",
    "bench",
    "viz",
    "commands",
]
#: Importable from anywhere.
SHARED = {"errors", "tolerances", "records", "typenames"}


def _layer(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] != "artiplan" or len(parts) < 2:
        return None
    return parts[1]


def _imports(path: Path) -> list[tuple[int, str]]:
    tree = ast.parse(path.read_text(), filename=str(path))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(node.lineno, alias.name) for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            found.append((node.lineno, node.module))
    return found


def _sources() -> list[Path]:
    return sorted(p for layer in LAYERS for p in (SRC / layer).rglob("*.py"))


@pytest.mark.parametrize("path", _sources(), ids=lambda p: str(p.relative_to(SRC)))
def test_imports_go_only_upward(path: Path) -> None:
    own = path.relative_to(SRC).parts[0]
    allowed = set(LAYERS[: LAYERS.index(own) + 1]) | SHARED
    bad = [
        f"{path.relative_to(SRC)}:{line}: imports {mod}"
        for line, mod in _imports(path)
        if (layer := _layer(mod)) is not None and layer not in allowed
    ]
    assert not bad, "layer violation (see docs/design/interfaces.md):\n" + "\n".join(bad)


def test_every_stage_is_known() -> None:
    stages = {p.name for p in SRC.iterdir() if p.is_dir() and not p.name.startswith("_")}
    assert stages <= set(LAYERS), f"unknown stage folders: {stages - set(LAYERS)}"
