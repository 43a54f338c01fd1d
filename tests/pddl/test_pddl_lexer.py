"""The lexer (string methods) against the regular-expression lexer it replaced, on random text.

The reference below is the lexer as it was written with ``re``: its tokens, lines, columns and
warnings, and its reading of numbers, are the definition the faster one must keep.
"""

from __future__ import annotations

import random
import re
from collections.abc import Callable

import pytest

from artiplan.errors import InputError, SourceLocation
from artiplan.pddl.lexer import SExpr, SList, Token, is_number, read_sexpr, tokenize

_TOKEN = re.compile(r"\s+|;[^\n]*|\(|\)|[^\s();]+")
_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


def reference_is_number(text: str) -> bool:
    return _NUMBER.match(text) is not None


def reference_tokenize(text: str, filename: str, warnings: list[str]) -> list[Token]:
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
            warnings.append(f"{lone.loc}: '? {s}' read as '?{s}' (a space after '?')")
            tokens.append(Token("?" + s, lone.loc))
        elif len(s) > 1 and s[0] == "-" and not reference_is_number(s):
            tokens.append(Token("-", SourceLocation(filename, line, col)))
            tokens.append(Token(s[1:], SourceLocation(filename, line, col + 1)))
        else:
            tokens.append(Token(s, SourceLocation(filename, line, col)))
    return tokens


#: Pieces random texts are made of: PDDL-ish words, numbers, signs, quirks, odd white space.
PIECES = ("(", ")", " ", "  ", "\t", "\n", "\r\n", "\n\n", ";", "; c (x)\n", "?", "? ", "?x",
          "-", "- ", "-t", "--", "-3", "-.5", "+2", "1", "1.", ".5", ".", "1e3", "2E-4", "1e",
          "e5", "1.2.3", "+-1", "3x", "x", "define", ":init", "\u00a0", "\u0663", "\u2028",
          "\x0b", "\x1c", "#t", "(at", "end)", "=", ">=")


@pytest.mark.parametrize("seed", range(300))
def test_tokens_same_as_the_regular_expression_lexer(seed: int) -> None:
    rng = random.Random(seed)
    text = "".join(rng.choice(PIECES) for _ in range(rng.randint(0, 60)))
    want_warnings: list[str] = []
    got_warnings: list[str] = []
    want = reference_tokenize(text, "f.pddl", want_warnings)
    got = tokenize(text, "f.pddl", got_warnings)
    assert [(t.text, t.loc) for t in got] == [(t.text, t.loc) for t in want], repr(text)
    assert got_warnings == want_warnings


NUMBERS = ("0", "12", "-3", "+4", ".5", "-.5", "5.", "1.25", "1e3", "1E-3", "-2.5e+7", ".5e1",
           "", "+", "-", ".", "-.", "e3", "1e", "1e+", "1.2.3", "1e3e4", "1e3E4", "1e3.5",
           "--1", "+-1", "1-", "0x1", "inf", "nan", "1_000", " 1", "1 ", "\u0663", "1\u0663",
           "\u00b2", "1e\u0663", "E5", "5E", "5e-", ".e1", "1.e1")


@pytest.mark.parametrize("text", NUMBERS)
def test_numbers_read_as_the_regular_expression_reads_them(text: str) -> None:
    assert is_number(text) is reference_is_number(text)


def test_random_numbers_read_the_same() -> None:
    rng = random.Random(7)
    alphabet = "0123456789..eE+-x\u0663 "
    for _ in range(5000):
        text = "".join(rng.choice(alphabet) for _ in range(rng.randint(0, 8)))
        assert is_number(text) is reference_is_number(text), repr(text)


def reference_read_sexpr(text: str, filename: str, warnings: list[str]) -> SList:
    tokens = reference_tokenize(text.removeprefix("\ufeff"), filename, warnings)
    if not tokens:
        raise InputError("empty file", SourceLocation(filename, 1, 1), expected="'(define'",
                         found="nothing")
    stack: list[tuple[list[SExpr], SourceLocation]] = []
    top: SList | None = None
    for tok in tokens:
        if top is not None:
            raise InputError("text after the end of the definition", tok.loc,
                             expected="end of file", found=tok.text)
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
            raise InputError("expected '(' at the start", tok.loc, expected="'('",
                             found=tok.text)
        else:
            stack[-1][0].append(tok)
    if stack:
        raise InputError("unbalanced '(': the file ends before it is closed", stack[-1][1],
                         expected="')'", found="end of file")
    assert top is not None
    return top


def outcome(read: Callable[[str, str, list[str]], SList], text: str) -> tuple[object, ...]:
    warnings: list[str] = []
    try:
        tree: object = read(text, "f.pddl", warnings)
    except InputError as exc:
        tree = ("error", str(exc))
    return tree, warnings


@pytest.mark.parametrize("seed", range(300))
def test_lists_same_as_before(seed: int) -> None:
    rng = random.Random(1000 + seed)
    pieces = PIECES + ("(", ")", "\ufeff") * 4  # mostly balanced-ish lists
    text = "".join(rng.choice(pieces) for _ in range(rng.randint(0, 50)))
    if rng.random() < 0.5:
        text = "(" + text + ")"
    assert outcome(read_sexpr, text) == outcome(reference_read_sexpr, text), repr(text)
