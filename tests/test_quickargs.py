"""artiplan.quickargs reads a plain command line as argparse does, and gives the rest to it."""

from __future__ import annotations

import importlib
import random
import subprocess
import sys
from typing import Any

import pytest

from artiplan import cli, quickargs


def argparse_reading(name: str, argv: list[str]) -> Any:
    parser, subparsers = cli.build_parser(name)
    module: Any = importlib.import_module(f"artiplan.commands.{cli.COMMANDS[name][0]}")
    module.add_arguments(subparsers[name])
    return parser.parse_args([name, *argv])


def quick_reading(name: str, argv: list[str]) -> quickargs.Namespace | None:
    module: Any = importlib.import_module(f"artiplan.commands.{cli.COMMANDS[name][0]}")
    return quickargs.parse(name, module.add_arguments, argv)


def recorded(name: str) -> list[Any] | None:
    """The recorded arguments of a command, None if quickargs leaves it to argparse."""
    module: Any = importlib.import_module(f"artiplan.commands.{cli.COMMANDS[name][0]}")
    recorder = quickargs._Recorder()
    try:
        module.add_arguments(recorder)
    except quickargs.Unsupported:
        return None
    return recorder.arguments


def sample(arg: Any, rng: random.Random) -> str:
    """A text argparse converts without error for this argument."""
    if arg.choices is not None:
        return str(rng.choice(list(arg.choices)))
    if arg.convert is int:
        return str(rng.randint(0, 50))
    if arg.convert is float:
        return rng.choice(["0.5", "3", "1e-3", "12.25"])
    texts = ["a.pddl", "dir/b.txt", "x y", "é", "3", "1,2", "a,b"]
    rng.shuffle(texts)
    if arg.convert is None:
        return texts[0]
    for text in texts:  # a type of the command's own: a text it accepts
        try:
            arg.convert(text)
        except Exception:  # noqa: BLE001 - argparse would refuse it: try the next
            continue
        return text
    raise AssertionError(f"no sample for {arg.dest}")


SUPPORTED = [name for name in cli.COMMANDS if recorded(name) is not None]


def test_plan_is_read_without_argparse() -> None:
    assert "plan" in SUPPORTED


@pytest.mark.parametrize("name", SUPPORTED)
@pytest.mark.parametrize("seed", range(25))
def test_random_plain_lines_read_as_argparse_reads_them(name: str, seed: int) -> None:
    rng = random.Random(seed)
    arguments = recorded(name)
    assert arguments is not None
    positionals = [sample(a, rng) for a in arguments if not a.flags]
    options: list[list[str]] = []
    for arg in arguments:
        if not arg.flags or (not arg.required and rng.random() < 0.5):
            continue
        flag = rng.choice(arg.flags)
        if arg.flag_value is not None:
            options.append([flag])
        elif flag.startswith("--") and rng.random() < 0.3:
            options.append([f"{flag}={sample(arg, rng)}"])
        else:
            options.append([flag, sample(arg, rng)])
    units = [[p] for p in positionals]
    for option in options:  # options anywhere among the positionals (kept in their order)
        units.insert(rng.randint(0, len(units)), option)
    argv = [text for unit in units for text in unit]
    quick = quick_reading(name, argv)
    assert quick is not None, argv
    want = argparse_reading(name, argv)
    assert vars(quick) == vars(want), argv
    assert {k: type(v) for k, v in vars(quick).items()} == \
        {k: type(v) for k, v in vars(want).items()}


D, P = "d.pddl", "p.pddl"


@pytest.mark.parametrize("argv", [
    ["-h"], [D, P, "--help"], ["--time", "3", D, P], ["--epsilon", "-1", D, P],
    ["--planner", "nope", D, P], [D], [D, P, "x"], ["--", D, P], ["-qo", "x", D, P],
    ["-ox", D, P], ["--quiet=1", D, P], ["--time-limit", "abc", D, P],
    ["-q", "-q", D, P], ["-o", D, P], [D, P, "-o"], ["-", P], ["-o=x", D, P],
])
def test_lines_left_to_argparse(argv: list[str]) -> None:
    assert quick_reading("plan", argv) is None


def test_a_line_left_to_argparse_gets_its_errors(capsys: pytest.CaptureFixture[str]) -> None:
    assert cli.main(["plan", "--planner", "nope", D, P]) == 2
    assert "invalid choice: 'nope'" in capsys.readouterr().err
    assert cli.main(["plan", "-h"]) == 0
    assert "--time-limit" in capsys.readouterr().out


def test_argparse_is_not_imported_for_a_plain_plan_line(tmp_path: Any) -> None:
    code = ("import sys\nfrom artiplan import cli\n"
            "cli.main(['plan', 'missing.pddl', 'missing-p.pddl', '-q'])\n"
            "print('argparse' in sys.modules, 're' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=tmp_path, check=True).stdout
    assert out.split() == ["False", "False"]


def test_a_recorder_refuses_what_it_does_not_read() -> None:
    def groups(parser: Any) -> None:
        parser.add_argument("x")
        parser.add_mutually_exclusive_group()

    def nargs(parser: Any) -> None:
        parser.add_argument("files", nargs="+")

    def count(parser: Any) -> None:
        parser.add_argument("-v", action="count")

    for add in (groups, nargs, count):
        assert quickargs.parse("x", add, ["a"]) is None
