"""Tokens and S-expressions of PDDL text, with 1-based line and column of every token.

``;`` starts a comment to the end of the line. A token ``-type`` (a type written right after
``?x -``, without a space) is split into ``-`` and ``type``; ``-3`` and ``-.5`` stay numbers.
A ``?`` standing alone before a name (``? g``, a quirk other tools accept) is read as ``?g``,
with a warning.
"""

from __future__ import annotations

import re

from artiplan.errors import InputError, SourceLocation
from artiplan.records import dataclass

_TOKEN = re.compile(r"\s+|;[^\n]*|\(|\)|[^\s();]+")
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


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
        return _NUMBER.match(self.text) is not None


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
    """True if ``text`` reads as a PDDL number (``.5``, ``-3``, ``1e-3``)."""
    return _NUMBER.match(text) is not None


def tokenize(text: str, filename: str, warnings: list[str] | None = None) -> list[Token]:
    """All tokens of ``text``, comments dropped, ``(`` and ``)`` as tokens of their own
    (harmless quirks read as meant, each noted in ``warnings``)."""
    tokens: list[Token] = []
    line, line_start = 1, 0
    for m in _TOKEN.finditer(text):
        s = m.group()
        start = m.start()
        if s[0].isspace() or s[0] == ";":
            newlines = s.count("\n")
            if newlines:
                line += newlines
                line_start = start + s.rfind("\n") + 1
            continue
        col = start - line_start + 1
        if tokens and tokens[-1].text == "?" and s not in ("(", ")"):
            lone = tokens.pop()
            if warnings is not None:
                warnings.append(f"{lone.loc}: '? {s}' read as '?{s}' (a space after '?')")
            tokens.append(Token("?" + s, lone.loc))
        elif len(s) > 1 and s[0] == "-" and not is_number(s):
            tokens.append(Token("-", SourceLocation(filename, line, col)))
            tokens.append(Token(s[1:], SourceLocation(filename, line, col + 1)))
        else:
            tokens.append(Token(s, SourceLocation(filename, line, col)))
    return tokens


def read_sexpr(text: str, filename: str, warnings: list[str] | None = None) -> SList:
    """The single top-level list of ``text`` (a domain or problem file); quirks noted in
    ``warnings``."""
    tokens = tokenize(text.removeprefix("\ufeff"), filename, warnings)  # no byte-order mark
    if not tokens:
        raise InputError(
            "empty file", SourceLocation(filename, 1, 1), expected="'(define'", found="nothing"
        )
    stack: list[tuple[list[SExpr], SourceLocation]] = []
    top: SList | None = None
    for tok in tokens:
        if top is not None:
            raise InputError(
                "text after the end of the definition", tok.loc, expected="end of file",
                found=tok.text,
            )
        if tok.text == "(":
            stack.append(([], tok.loc))
        elif tok.text == ")":
            if not stack:
                raise InputError("unbalanced ')'", tok.loc, expected="'('", found=")")
            items, loc = stack.pop()
            node = SList(tuple(items), loc, tok.loc)
            if stack:
                stack[-1][0].append(node)
            else:
                top = node
        elif not stack:
            raise InputError("expected '(' at the start", tok.loc, expected="'('", found=tok.text)
        else:
            stack[-1][0].append(tok)
    if stack:
        raise InputError(
            "unbalanced '(': the file ends before it is closed", stack[-1][1],
            expected="')'", found="end of file",
        )
    assert top is not None
    return top
