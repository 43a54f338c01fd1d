"""The command line's shared behaviour: help, version, unknown commands, exit codes."""

from __future__ import annotations

import subprocess
import sys

import pytest

from artiplan.cli import COMMANDS, main
from artiplan.errors import ExitCode


def test_help_lists_every_command(capsys) -> None:  # type: ignore[no-untyped-def]
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    for name in COMMANDS:
        assert name in out


@pytest.mark.parametrize("argv", [[name, "--help"] for name in COMMANDS]
                         + [["world", "snapshot", "--help"], ["world", "ontology", "--help"]],
                         ids=lambda a: " ".join(a[:-1]))
def test_every_command_prints_its_help(argv: list[str], capsys) -> None:  # type: ignore[no-untyped-def]
    # argparse formats help texts with %: a stray % in one crashed `artiplan demo --help`
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: artiplan ") and "--help" in out


def test_top_level_help_before_a_command_lists_every_command(capsys) -> None:  # type: ignore[no-untyped-def]
    # `artiplan plan ...` builds only its own parser; the top-level help needs them all
    assert main(["--help", "plan"]) == 0
    out = capsys.readouterr().out
    assert all(name in out for name in COMMANDS)
    assert main(["plann"]) == ExitCode.USAGE
    assert "choose from" in capsys.readouterr().err


def test_plan_imports_only_what_planning_needs(tmp_path) -> None:  # type: ignore[no-untyped-def]
    """`artiplan plan` starts fast: none of the heavy or unrelated packages on its path."""
    run = [sys.executable, "-m", "artiplan"]
    subprocess.run([*run, "generate", "--links", "3", "--model", "ucm", "-o", str(tmp_path)],
                   check=True, capture_output=True)
    problem = next(p for p in tmp_path.glob("*.pddl") if "domain" not in p.name)
    code = ("import sys; from artiplan.cli import main; "
            f"rc = main(['plan', {str(tmp_path / 'domain.pddl')!r}, {str(problem)!r}, '-q', "
            f"'-o', {str(tmp_path / 'plan.txt')!r}]); print(rc); print(' '.join(sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.splitlines()
    assert out[-2] == "0" and (tmp_path / "plan.txt").read_text().strip()
    loaded = set(out[-1].split())
    heavy = {"numpy", "scipy", "unified_planning", "mujoco", "owlready2", "matplotlib",
             "dataclasses", "inspect", "shutil", "typing", "artiplan.backends", "artiplan.world",
             "artiplan.execution", "artiplan.bench", "artiplan.viz", "artiplan.up"}
    assert not loaded & heavy, sorted(loaded & heavy)


@pytest.mark.parametrize("columns", [None, "50", "0", "wide"])
def test_help_is_as_wide_as_argparse_makes_it(columns: str | None, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    import argparse
    import shutil

    from artiplan import cli

    if columns is None:
        monkeypatch.delenv("COLUMNS", raising=False)
    else:
        monkeypatch.setenv("COLUMNS", columns)
    assert cli.terminal_columns() == shutil.get_terminal_size().columns
    texts = []
    for formatter in (argparse.HelpFormatter, cli.HelpFormatter):
        p = argparse.ArgumentParser(prog="x", description="word " * 40, formatter_class=formatter)
        p.add_argument("--flag", help="a long help text " * 8)
        texts.append(p.format_help())
    assert texts[0] == texts[1]


def test_no_command_is_a_usage_error(capsys) -> None:  # type: ignore[no-untyped-def]
    assert main([]) == ExitCode.USAGE


def test_bad_option_is_a_usage_error(capsys) -> None:  # type: ignore[no-untyped-def]
    assert main(["--no-such-option"]) == ExitCode.USAGE


def test_module_entry_point_runs() -> None:
    proc = subprocess.run(
        [sys.executable, "-m", "artiplan", "--version"], capture_output=True, text=True, check=False
    )
    assert proc.returncode == 0
    assert proc.stdout.startswith("artiplan ")


def test_exit_codes_match_the_conventions() -> None:
    expected = {
        "OK": 0,
        "INTERNAL": 1,
        "USAGE": 2,
        "BAD_INPUT": 3,
        "INVALID_PLAN": 4,
        "UNSOLVABLE": 5,
        "NO_PLAN": 6,
        "TIME_LIMIT": 7,
        "MEMORY_LIMIT": 8,
        "EXTERNAL_TOOL": 9,
    }
    assert {c.name: int(c) for c in ExitCode} == expected


def test_the_collector_threshold_is_the_process_entry_points_alone(capsys) -> None:  # type: ignore[no-untyped-def]
    # main(argv) from a caller's code leaves the caller's process settings alone; the console
    # script (argv None) raises the first generation's threshold for its own process
    import gc

    from artiplan.cli import GC_THRESHOLD

    before = gc.get_threshold()
    assert main(["--version"]) == 0
    assert gc.get_threshold() == before
    code = ("import gc, sys; sys.argv = ['artiplan', '--version']; from artiplan.cli import main; "
            "main(); print(gc.get_threshold()[0])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert int(out[-1]) == GC_THRESHOLD != before[0]
