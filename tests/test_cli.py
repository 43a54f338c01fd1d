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
