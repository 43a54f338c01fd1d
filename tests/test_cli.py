"""The command line's shared behaviour: help, version, unknown commands, exit codes."""

from __future__ import annotations

import subprocess
import sys

from artiplan.cli import COMMANDS, main
from artiplan.errors import ExitCode


def test_help_lists_every_command(capsys) -> None:  # type: ignore[no-untyped-def]
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    for name in COMMANDS:
        assert name in out


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
