"""The limited runner on tiny Python children: exit codes, output, CPU and memory limits."""

from __future__ import annotations

import sys

from artiplan.backends.runner import Limits, run_limited

BUSY = "while True: pass"
GREEDY = (
    "import time\nblocks = []\n"
    "while True:\n    blocks.append(bytearray(8 << 20)); time.sleep(0.01)"
)
SLEEPY = "import time; time.sleep(60)"


def test_exit_code_and_output_are_kept() -> None:
    code = "import sys; print('out'); print('err', file=sys.stderr); sys.exit(3)"
    outcome = run_limited([sys.executable, "-c", code], Limits(time_limit=10))
    assert outcome.returncode == 3
    assert outcome.stdout.strip() == "out" and outcome.stderr.strip() == "err"
    assert outcome.limit_hit is None


def test_cpu_limit_kills_a_busy_child() -> None:
    # The kill and the reported status, not a CPU figure: on a loaded machine the measured
    # CPU time of a killed child varies (it was 0.75 s for a 1 s limit once).
    outcome = run_limited([sys.executable, "-c", BUSY], Limits(time_limit=1.0))
    assert outcome.limit_hit == "time"
    assert outcome.returncode != 0  # killed: BUSY never exits by itself
    assert outcome.cpu_s > 0.0


def test_wall_watchdog_kills_a_sleeping_child() -> None:
    limits = Limits(time_limit=0.5, wall_factor=1.0, wall_slack=0.5)
    outcome = run_limited([sys.executable, "-c", SLEEPY], limits)
    assert outcome.limit_hit == "wall"
    assert outcome.wall_s < 5.0 and outcome.cpu_s < 0.5


def test_memory_limit_kills_a_greedy_child() -> None:
    outcome = run_limited([sys.executable, "-c", GREEDY], Limits(time_limit=30, memory_limit=120))
    assert outcome.limit_hit == "memory"
    assert outcome.peak_mb > 100
    assert outcome.wall_s < 20
