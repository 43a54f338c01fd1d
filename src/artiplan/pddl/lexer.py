"""Tokens and S-expressions of PDDL text, with 1-based line and column of every token.

``;`` starts a comment to the end of the line. A token ``-type`` (a type written right after
``?x -``, without a space) is split into ``-`` and ``type``; ``-3`` and ``-.5`` stay numbers.
A ``?`` standing alone before a name (``? g``, a quirk other tools accept) is read as ``?g``,
with a warning.
"""

from __future__ import annotations

from artiplan.errors import InputError, SourceLocation
from artiplan.records import dataclass


@dataclass(frozen=True)
class Token:
    """One atom of the text (a name, variable, number or keyword)."""

    text: str
    loc: SourceLocation

    @property
    def lower(self) -> str:
        """The text lower-cased (PDDL names are case-insensitive)."""
        return self.text.lower()

    def is_number(self) -> bool:
        """True if the token reads as a number."""
        return is_number(self.text)


@dataclass(frozen=True)
class SList:
    """A parenthesised list; ``loc`` is its opening parenthesis, ``end`` its closing one."""

    items: tuple[SExpr, ...]
    loc: SourceLocation
    end: SourceLocation

    def head(self) -> str | None:
        """The lower-cased first token, if the list starts with one."""
        if self.items and isinstance(self.items[0], Token):
            return self.items[0].lower
        return None


SExpr = Token | SList


def describe(expr: SExpr | None) -> str:
    """A short text of ``expr`` for error messages (the ``found`` part)."""
    if expr is None:
        return "end of list"
    if isinstance(expr, Token):
        return expr.text
    head = expr.head()
    return f"({head} ...)" if head is not None else "(...)"


def is_number(text: str) -> bool:
    """True if ``text`` reads as a PDDL number (``.5``, ``-3``, ``1e-3``): an optional sign,
    digits with at most one ``.`` (at least one digit), an optional exponent ``e``/``E``, sign,
    digits. (String methods, not ``re``: importing it is a share of a short command's start.)"""
    body = text[1:] if text[:1] in ("+", "-") else text
    cut = min((i for i in (body.find("e"), body.find("E")) if i >= 0), default=len(body))
    mantissa, exponent = body[:cut], body[cut + 1:]
    if cut < len(body):
        exponent = exponent[1:] if exponent[:1] in ("+", "-") else exponent
        if not exponent.isdecimal():
            return False
    whole, dot, fraction = mantissa.partition(".")
    if not dot:
        return whole.isdecimal()
    return bool(whole or fraction) and all(p == "" or p.isdecimal() for p in (whole, fraction))


def tokenize(text: str, filename: str, warnings: list[str] | None = None) -> list[Token]:
    """All tokens of ``text``, comments dropped, ``(`` and ``)`` as tokens of their own
    (harmless quirks read as meant, each noted in ``warnings``)."""
    return [Token(s, SourceLocation(filename, line, col))
            for s, line, col in _scan(text, filename, warnings)]


def _scan(text: str, filename: str, warnings: list[str] | None) -> list[tuple[str, int, int]]:
    """The tokens of ``text`` as (text, line, column): what :func:`tokenize` makes tokens of
    (:func:`read_sexpr` makes only the tokens and locations its lists keep)."""
    out: list[tuple[str, int, int]] = []
    for line, row in enumerate(text.split("\n"), 1):
        comment = row.find(";")
        if comment >= 0:
            row = row[:comment]
        end = 0
        # between two tokens there is only white space, so each is found from the last's end
        for s in row.replace("(", " ( ").replace(")", " ) ").split():
            start = row.find(s, end)
            end = start + len(s)
            col = start + 1
            if out and out[-1][0] == "?" and s not in ("(", ")"):
                _, lone_line, lone_col = out.pop()
                if warnings is not None:
                    warnings.append(f"{SourceLocation(filename, lone_line, lone_col)}: "
                                    f"'? {s}' read as '?{s}' (a space after '?')")
                out.append(("?" + s, lone_line, lone_col))
            elif len(s) > 1 and s[0] == "-" and not is_number(s):
                out.append(("-", line, col))
                out.append((s[1:], line, col + 1))
            else:
                out.append((s, line, col))
    return out


def read_sexpr(text: str, filename: str, warnings: list[str] | None = None) -> SList:
    """The single top-level list of ``text`` (a domain or problem file); quirks noted in
    ``warnings``."""
    scanned = _scan(text.removeprefix("\ufeff"), filename, warnings)  # no byte-order mark
    if not scanned:
        raise InputError(
            "empty file", SourceLocation(filename, 1, 1), expected="'(define'", found="nothing"
        )
    stack: list[tuple[list[SExpr], SourceLocation]] = []
    top: SList | None = None
    for s, line, col in scanned:
        loc = SourceLocation(filename, line, col)
        if top is not None:
            raise InputError(
                "text after the end of the definition", loc, expected="end of file", found=s,
            )
        if s == "(":
            stack.append(([], loc))
        elif s == ")":
            if not stack:
                raise InputError("unbalanced ')'", loc, expected="'('", found=")")
            items, start = stack.pop()
            node = SList(tuple(items), start, loc)
            if stack:
                stack[-1][0].append(node)
            else:
                top = node
        elif not stack:
            raise InputError("expected '(' at the start", loc, expected="'('", found=s)
        else:
            stack[-1][0].append(Token(s, loc))
    if stack:
        raise InputError(
            "unbalanced '(': the file ends before it is closed", stack[-1][1],
            expected="')'", found="end of file",
        )
    assert top is not None
    return top
