"""The loader tells paths from PDDL text: ``os.PathLike`` (``Path``, the CLI's ``FilePath``)
is always a file, a ``str`` is text when it looks like PDDL."""

from __future__ import annotations

from pathlib import Path

import pytest

from artiplan.commands import FilePath
from artiplan.errors import InputError
from artiplan.pddl.loader import read_source

TEXT = "(define (domain d))\n"


def test_pathlike_is_read_as_a_file_even_when_its_name_looks_like_pddl(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    Path("(odd).pddl").write_text(TEXT)
    assert read_source(FilePath("(odd).pddl"), "<domain>") == (TEXT, "(odd).pddl")
    assert read_source(Path("(odd).pddl"), "<domain>") == (TEXT, "(odd).pddl")
    # a plain str that starts with "(" is PDDL text, not a file name
    assert read_source("(odd).pddl", "<domain>") == ("(odd).pddl", "<domain>")


def test_plain_str_path_and_missing_file(tmp_path: Path) -> None:
    f = tmp_path / "d.pddl"
    f.write_text(TEXT)
    assert read_source(str(f), "<domain>") == (TEXT, str(f))
    with pytest.raises(InputError, match="cannot read"):
        read_source(FilePath(str(tmp_path / "missing.pddl")), "<domain>")
