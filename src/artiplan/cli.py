"""The ``artiplan`` command: one entry point, one sub-command per pipeline stage.

Each sub-command lives in ``artiplan.commands.<module>`` and exposes two functions:
``add_arguments(parser)`` and ``run(args) -> int``. Modules are imported only when their command
runs, so ``artiplan --help`` is fast and a broken optional dependency breaks only its command.
Exit codes: :class:`artiplan.errors.ExitCode` (shared/docs/conventions.md).
"""

from __future__ import annotations

import gc
import importlib
import os
import sys
import time

from artiplan import __version__, quickargs
from artiplan.errors import ArtiplanError, ExitCode

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    import argparse
    from collections.abc import Sequence
    from typing import Any

#: The cyclic collector's first-generation threshold in an artiplan process (default 700).
GC_THRESHOLD = 50_000

#: name -> (module under artiplan.commands, one-line help). Order = the pipeline.
COMMANDS: dict[str, tuple[str, str]] = {
    "generate": ("generate", "write one PDDL+ domain and problem from options or configurations"),
    "suite": ("suite", "write the paper's 240-problem benchmark suite"),
    "draw": ("draw", "draw a configuration in 3D (PNG), with an optional target ghost"),
    "parse": ("parse", "parse a PDDL+ domain (and problem), report warnings, print it back"),
    "ground": ("ground", "ground a PDDL+ problem and report counts and time"),
    "plan": ("plan", "plan with artiplan's exact-time PDDL+ planner (or --planner enhsp|kairos)"),
    "validate": ("validate", "validate a plan with VAL's semantics"),
    "simulate": ("simulate", "simulate a plan: trajectory CSV and a plot of the angles"),
    "bench": ("bench", "run planners on a suite; results as JSON Lines, resumable"),
    "report": ("report", "Table 1, PAR10 and cactus plots from benchmark results"),
    "world": ("world", "the simulated MuJoCo world: snapshots, camera images"),
    "demo": ("demo", "the main job on built-in defaults"),
    "fidelity": ("fidelity", "measure each gravity model's prediction error against physics"),
}

#: Commands that end the process at once when done (their time limit is the process's).
QUICK_EXIT = frozenset({"plan"})

def process_start() -> float:
    """When this process started [s since the epoch] (Linux /proc; else: now)."""
    try:
        with open("/proc/self/stat") as fh:
            start_ticks = int(fh.read().rsplit(")", 1)[1].split()[19])
        with open("/proc/uptime") as fh:
            uptime = float(fh.read().split()[0])
        return time.time() - max(0.0, uptime - start_ticks / os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return time.time()


def terminal_columns() -> int:
    """``shutil.get_terminal_size().columns``: COLUMNS, else stdout's terminal, else 80."""
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns > 0:
        return columns
    try:
        return os.get_terminal_size(sys.__stdout__.fileno()).columns or 80  # type: ignore[union-attr]
    except (AttributeError, ValueError, OSError):
        return 80


def _help_formatter() -> type[argparse.HelpFormatter]:
    """argparse's formatter, as wide as argparse makes it, without importing ``shutil`` (and
    its compression modules: a noticeable share of a short command's start) to find out. Made
    on first use: argparse itself is imported only when a command line needs it."""
    made: type[argparse.HelpFormatter] | None = globals().get("HelpFormatter")
    if made is not None:
        return made
    import argparse

    class HelpFormatter(argparse.HelpFormatter):
        """argparse's formatter, as wide as the terminal, without ``shutil``."""

        def __init__(self, prog: str, indent_increment: int = 2, max_help_position: int = 24,
                     width: int | None = None) -> None:
            super().__init__(prog, indent_increment, max_help_position,
                             terminal_columns() - 2 if width is None else width)

    globals()["HelpFormatter"] = HelpFormatter
    return HelpFormatter


def __getattr__(name: str) -> Any:
    if name == "HelpFormatter":  # cli.HelpFormatter, made on first use
        return _help_formatter()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


REPORT_URL = "the project's issue tracker (include the command line and the traceback above)"


def build_parser(
    only: str | None = None,
) -> tuple[argparse.ArgumentParser, dict[str, argparse.ArgumentParser]]:
    """The parser and the sub-commands' parsers (empty: ``add_arguments`` fills them); with
    ``only``, that sub-command's alone (a parser a command costs a noticeable share of a short
    command's start)."""
    import argparse

    formatter = _help_formatter()
    parser = argparse.ArgumentParser(
        prog="artiplan",
        description="Plan and execute the reshaping of articulated objects with PDDL+ and gravity.",
        formatter_class=formatter,
    )
    parser.add_argument("--version", action="version", version=f"artiplan {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers = {}
    for name, (_module, help_text) in COMMANDS.items():
        if only is None or name == only:
            subparsers[name] = sub.add_parser(name, help=help_text, description=help_text,
                                              formatter_class=formatter)
    return parser, subparsers


def _load(name: str) -> object | None:
    module_name, _ = COMMANDS[name]
    try:
        return importlib.import_module(f"artiplan.commands.{module_name}")
    except ModuleNotFoundError as exc:
        if exc.name == f"artiplan.commands.{module_name}":
            return None
        raise


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; returns the exit code (also used by ``python -m artiplan``).

    Called as the process's entry point (``argv`` None), ``plan`` ends the process itself
    once its output is flushed (see ``QUICK_EXIT``)."""
    argv_is_process = argv is None
    if argv_is_process:
        # A command builds ~10^5 long-lived objects (modules, classes, the grounded task) in
        # its first tenth of a second; at the default threshold (700) the cyclic collector
        # walks them again and again: ~5% of a small 'plan'. A process-wide setting, so
        # only for the process's own entry point, not for callers of main(argv).
        gc.set_threshold(GC_THRESHOLD, *gc.get_threshold()[1:])
    argv = list(sys.argv[1:] if argv is None else argv)
    # Find the sub-command first so only its module is imported, and only its parser built:
    # all of them only for the top-level help and errors (an option before the command, an
    # unknown command), which list every command.
    name = next((a for a in argv if not a.startswith("-")), None)
    alone = name in COMMANDS and argv.index(name) == 0
    module = None
    if name in COMMANDS:
        module = _load(name)
        if module is None:
            print(f"artiplan: command {name!r} is not available in this version", file=sys.stderr)
            return int(ExitCode.USAGE)
    args: Any = None
    if alone:  # a plain command line is read without argparse (artiplan.quickargs)
        args = quickargs.parse(name, module.add_arguments, argv[1:])  # type: ignore[attr-defined,arg-type]
    if args is None:
        parser, subparsers = build_parser(name if alone else None)
        if module is not None:
            module.add_arguments(subparsers[name])  # type: ignore[attr-defined,index]
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # argparse: --help gives 0, bad options 2
            return int(exc.code or 0)
    if args.command is None:
        parser.print_help()  # only argparse reads a line without a command
        return int(ExitCode.USAGE)
    # When the command started [s since the epoch]: the process's start when it is the entry
    # point (a time limit then covers Python's start-up too), else now.
    args.started_at = process_start() if argv_is_process else time.time()
    try:
        code = int(module.run(args))  # type: ignore[attr-defined]
        if name in QUICK_EXIT and argv_is_process:
            # Freeing a large search graph at interpreter exit takes a noticeable share of a
            # short time limit; nothing is left to clean up (files are closed), so leave now.
            sys.stdout.flush()
            sys.stderr.flush()
            os._exit(code)
        return code
    except ArtiplanError as exc:
        print(f"artiplan {args.command}: error: {exc}", file=sys.stderr)
        return int(exc.exit_code)
    except KeyboardInterrupt:
        print(f"artiplan {args.command}: interrupted", file=sys.stderr)
        return 130
    except Exception:
        import traceback  # only now: it costs a noticeable share of a short command's start

        traceback.print_exc()
        print(
            f"artiplan {args.command}: internal error (a bug). Please report it to {REPORT_URL}.",
            file=sys.stderr,
        )
        return int(ExitCode.INTERNAL)


if __name__ == "__main__":
    sys.exit(main())
