"""Names that appear only in annotations, without importing :mod:`typing` at run time.

Start-up: ``typing`` costs an ``artiplan`` process a few milliseconds. mypy reads any name
``TYPE_CHECKING`` as true and so sees the real names; at run time they are placeholders, which
is enough because every module has ``from __future__ import annotations`` and only uses them in
annotations (never in a run-time alias such as ``X = Literal[...]``).
"""

from __future__ import annotations

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any as Any
    from typing import Literal as Literal
else:
    Any = Literal = object
