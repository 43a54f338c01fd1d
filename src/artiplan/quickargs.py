"""argparse's reading of a plain sub-command line, without importing argparse.

``artiplan plan D P -o OUT`` is most often run on small problems, where importing ``argparse``
(with ``gettext``, ``locale`` and ``re``) and building its parsers is a noticeable share of the
whole process. A command's ``add_arguments(parser)`` is run here against a recorder, which keeps
the ``add_argument`` calls; a command line that uses only what the recorder understands, in the
plain forms below, is read from them, with the values argparse would give. Anything else gives
None and argparse reads the line as ever (and prints its help or errors): there is one
definition of each command's options, and tests/test_quickargs.py checks the two readings
agree.

Read here: positionals (no ``nargs``), ``--long VALUE``, ``--long=VALUE``, ``-s VALUE``, flags
(``store_true``/``store_false``), ``type``, ``default``, ``choices``, ``required``, ``dest``;
each option at most once. Left to argparse: ``-h``, abbreviations, ``--``, ``-sVALUE``, grouped
flags, a value that starts with ``-``, a conversion or choice that fails, a missing or extra
positional, ``nargs``, other actions, argument groups.
"""

from __future__ import annotations

TYPE_CHECKING = False  # read as true by mypy; typing is not imported at run time (start-up)
if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from typing import Any

__all__ = ["Namespace", "Unsupported", "parse"]

#: ``add_argument`` keywords that only change help texts.
_COSMETIC = frozenset({"help", "metavar"})
_STORE = (None, "store")
_FLAGS = {"store_true": (False, True), "store_false": (True, False)}


class Unsupported(Exception):
    """The recorder met something this module does not read (argparse then does it all)."""


class Namespace:
    """``argparse.Namespace``: the parsed values as attributes (equal by ``vars()``)."""

    def __init__(self, **values: Any) -> None:
        self.__dict__.update(values)

    def __eq__(self, other: object) -> bool:
        return vars(self) == vars(other) if hasattr(other, "__dict__") else NotImplemented

    def __repr__(self) -> str:
        return "Namespace(" + ", ".join(f"{k}={v!r}" for k, v in vars(self).items()) + ")"

    def __contains__(self, key: str) -> bool:
        return key in self.__dict__


class _Argument:
    """One recorded ``add_argument`` call, reduced to what reading a value needs."""

    __slots__ = ("flags", "dest", "convert", "default", "choices", "required", "flag_value")

    def __init__(self, names: tuple[str, ...], options: dict[str, Any]) -> None:
        unknown = set(options) - _COSMETIC - {"type", "default", "choices", "required", "dest",
                                              "action"}
        action = options.get("action")
        if unknown or not names or not all(isinstance(n, str) and n for n in names):
            raise Unsupported(f"add_argument{names}: {sorted(unknown)}")
        if action not in _STORE and action not in _FLAGS:
            raise Unsupported(f"action {action!r}")
        positional = not names[0].startswith("-")
        if positional and (len(names) > 1 or "dest" in options or "required" in options):
            raise Unsupported(f"positional {names}")
        if not positional and not all(n.startswith("-") for n in names):
            raise Unsupported(f"option names {names}")
        self.flags = () if positional else names
        self.dest: str = options.get("dest") or (names[0] if positional else _dest(names))
        self.flag_value: bool | None = None
        self.convert: Callable[[str], Any] | None = options.get("type")
        self.choices = options.get("choices")
        self.required = bool(options.get("required", positional))
        if action in _FLAGS:
            if {"type", "choices"} & set(options):
                raise Unsupported(f"{action} with a type or choices")
            default, self.flag_value = _FLAGS[action]
            self.default = options.get("default", default)
        else:
            self.default = options.get("default")
            if isinstance(self.default, str) and self.convert is not None:
                # argparse converts a string default as if it were given
                self.default = self.convert(self.default)


def _dest(names: tuple[str, ...]) -> str:
    """argparse's ``dest`` of an option: its first long name, else its first name."""
    first = next((n for n in names if n.startswith("--")), names[0])
    return first.lstrip("-").replace("-", "_")


class _Recorder:
    """Stands in for the sub-command's parser while ``add_arguments`` runs."""

    def __init__(self) -> None:
        self.arguments: list[_Argument] = []

    def add_argument(self, *names: str, **options: Any) -> None:
        self.arguments.append(_Argument(names, options))

    def __getattr__(self, name: str) -> Any:
        raise Unsupported(f"parser.{name}")


def parse(command: str, add_arguments: Callable[[Any], None],
          argv: Sequence[str]) -> Namespace | None:
    """The namespace argparse would return for ``artiplan COMMAND ARGV...``, or None when
    argparse must read ``argv`` itself (see the module docstring)."""
    recorder = _Recorder()
    try:
        add_arguments(recorder)
    except Unsupported:
        return None
    positionals = [a for a in recorder.arguments if not a.flags]
    by_flag = {flag: a for a in recorder.arguments for flag in a.flags}
    values: dict[str, Any] = {}
    given_positionals: list[str] = []
    i = 0
    try:
        while i < len(argv):
            token = argv[i]
            i += 1
            if not token.startswith("-"):
                given_positionals.append(token)
                continue
            name, eq, attached = token.partition("=")
            arg = by_flag.get(name)
            if arg is None or arg.dest in values or (eq and not name.startswith("--")):
                return None
            if arg.flag_value is not None:
                if eq:
                    return None
                values[arg.dest] = arg.flag_value
                continue
            if eq:
                text = attached
            else:
                if i >= len(argv) or argv[i].startswith("-"):
                    return None
                text, i = argv[i], i + 1
            values[arg.dest] = _value(arg, text)
        if len(given_positionals) != len(positionals):
            return None
        for arg, text in zip(positionals, given_positionals, strict=True):
            values[arg.dest] = _value(arg, text)
    except _LeaveToArgparse:
        return None
    if any(a.required and a.dest not in values for a in recorder.arguments if a.flags):
        return None
    result = Namespace(command=command)
    for arg in recorder.arguments:
        setattr(result, arg.dest, values.get(arg.dest, arg.default))
    return result


class _LeaveToArgparse(Exception):
    """A value argparse would refuse, or might: it then reads the line (and says why)."""


def _value(arg: _Argument, text: str) -> Any:
    try:
        value = text if arg.convert is None else arg.convert(text)
    except Exception as exc:  # argparse reports ValueError, TypeError, ArgumentTypeError
        raise _LeaveToArgparse(text) from exc
    if arg.choices is not None and value not in arg.choices:
        raise _LeaveToArgparse(text)
    return value
