"""Run a planner program as a child process under a CPU-time and a memory limit.

The same runner serves every backend, so limits and measurements are the same for all:

- CPU time: ``RLIMIT_CPU`` on the child (via ``prlimit``; the kernel kills it) plus a poll of
  the process tree's CPU time (children too), and a wall-clock watchdog at
  ``wall_factor`` x the limit + ``wall_slack`` (a child that sleeps or waits on I/O burns no
  CPU). The watchdog is generous because the machine may be shared: a loaded machine stretches
  wall time, not CPU time.
- Memory: the resident memory (RSS) of the whole process tree is polled with psutil and the tree
  is killed when it exceeds the limit. ``RLIMIT_AS`` is not used: the JVM reserves far more
  address space than it touches and would fail at start.
- The child gets ``SIGKILL`` when the thread that started it dies (``setpriv --pdeathsig``), so a
  killed benchmark leaves no orphan planners behind.

Measured: CPU time of the child and its descendants (``wait4`` rusage, or the last poll if
larger), wall time, peak RSS of the tree.
"""

from __future__ import annotations

import contextlib
import math
import os
import resource
import shutil
import signal
import subprocess
import tempfile
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import IO

import psutil

MIB = 1024 * 1024
#: Messages of a timeout row, by which limit stopped the run.
TIMEOUT_MESSAGES = {
    "time": "CPU-time limit reached",
    "wall": "wall-clock watchdog (the machine was too loaded or the planner hung)",
}


@dataclass(frozen=True)
class Limits:
    """Limits of one run.

    ``time_limit``: CPU time [s] (None: none); ``memory_limit``: RSS of the process tree [MiB]
    (None: none); the wall-clock watchdog fires at ``wall_factor * time_limit + wall_slack`` [s];
    ``poll_interval``: how often the tree is measured [s].
    """

    time_limit: float | None = None
    memory_limit: float | None = None
    wall_factor: float = 3.0
    wall_slack: float = 30.0
    poll_interval: float = 0.05

    @property
    def wall_cap(self) -> float | None:
        """When the wall-clock watchdog fires [s] (None without a time limit)."""
        if self.time_limit is None:
            return None
        return self.wall_factor * self.time_limit + self.wall_slack


@dataclass(frozen=True)
class RunOutcome:
    """What happened to the child. ``limit_hit``: ``"time"`` (CPU), ``"wall"`` (the watchdog),
    ``"memory"`` or None."""

    returncode: int
    stdout: str
    stderr: str
    cpu_s: float
    wall_s: float
    peak_mb: float
    limit_hit: str | None


def _wrapped(cmd: Sequence[str], limits: Limits) -> list[str]:
    """Prefix the command with the kernel-side guards that are available here."""
    prefix: list[str] = []
    setpriv = shutil.which("setpriv")
    if setpriv:
        prefix += [setpriv, "--pdeathsig", "KILL", "--"]
    prlimit = shutil.which("prlimit")
    if prlimit and limits.time_limit is not None:
        soft = max(1, math.ceil(limits.time_limit))
        # Soft limit: SIGXCPU; hard limit 2 s later: SIGKILL (a child may ignore SIGXCPU).
        prefix += [prlimit, f"--cpu={soft}:{soft + 2}", "--"]
    return prefix + list(cmd)


def _tree_usage(proc: psutil.Process) -> tuple[float, float]:
    """(CPU seconds, RSS in MiB) of a process and all its descendants; 0 for vanished ones."""
    cpu = rss = 0.0
    try:
        members = [proc, *proc.children(recursive=True)]
    except psutil.Error:
        return cpu, rss
    for member in members:
        try:
            with member.oneshot():
                times = member.cpu_times()
                cpu += times.user + times.system + times.children_user + times.children_system
                rss += member.memory_info().rss / MIB
        except psutil.Error:
            continue
    return cpu, rss


def _kill_tree(pid: int) -> None:
    """SIGKILL the child's process group (it leads its own session) and any stragglers."""
    try:
        for child in psutil.Process(pid).children(recursive=True):
            child.kill()
    except psutil.Error:
        pass
    with contextlib.suppress(OSError):
        os.killpg(pid, signal.SIGKILL)


def run_limited(
    cmd: Sequence[str],
    limits: Limits,
    *,
    cwd: str | Path | None = None,
    env: dict[str, str] | None = None,
    max_output: int | None = None,
) -> RunOutcome:
    """Run ``cmd`` to completion or until a limit is hit; never raises for the child's failures.

    ``max_output`` [bytes]: of a longer stdout or stderr keep the first and last halves only.

    Raises:
        FileNotFoundError: the program does not exist (callers turn it into ExternalToolError).
    """
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        start = time.monotonic()
        proc = subprocess.Popen(
            _wrapped(cmd, limits), stdout=out, stderr=err, stdin=subprocess.DEVNULL,
            cwd=cwd, env=env, start_new_session=True,
        )
        status, rusage, peak, polled_cpu, hit = _watch(proc, limits, start)
        wall = time.monotonic() - start
        stdout, stderr = _read(out, max_output), _read(err, max_output)
    cpu = max(rusage.ru_utime + rusage.ru_stime, polled_cpu) if rusage else polled_cpu
    peak = max(peak, rusage.ru_maxrss / 1024.0) if rusage else peak  # ru_maxrss is KiB on Linux
    code = os.waitstatus_to_exitcode(status)
    proc.returncode = code
    if hit is None and limits.time_limit is not None and (
        code == -signal.SIGXCPU or (code == -signal.SIGKILL and cpu >= 0.9 * limits.time_limit)
    ):
        hit = "time"  # the kernel's RLIMIT_CPU did it
    return RunOutcome(code, stdout, stderr, cpu, wall, peak, hit)


def _read(fh: IO[bytes], max_output: int | None) -> str:
    """The text of a finished child's output file (head and tail if over ``max_output``)."""
    size = fh.seek(0, os.SEEK_END)
    fh.seek(0)
    if max_output is None or size <= max_output:
        data = fh.read()
    else:
        half = max_output // 2
        data = fh.read(half) + b"\n...\n"
        fh.seek(size - half)
        data += fh.read()
    return data.decode("utf-8", errors="replace")


def _watch(
    proc: subprocess.Popen[bytes], limits: Limits, start: float
) -> tuple[int, resource.struct_rusage | None, float, float, str | None]:
    """Poll the child until it exits; kill it at a limit. Returns (status, rusage, peak MiB,
    last polled CPU s, limit hit)."""
    try:
        ps = psutil.Process(proc.pid)
    except psutil.Error:
        ps = None
    peak = polled_cpu = 0.0
    hit: str | None = None
    wall_cap = limits.wall_cap
    while True:
        pid, status, rusage = os.wait4(proc.pid, os.WNOHANG)
        if pid == proc.pid:
            return status, rusage, peak, polled_cpu, hit
        if ps is not None and hit is None:
            cpu, rss = _tree_usage(ps)
            polled_cpu = max(polled_cpu, cpu)
            peak = max(peak, rss)
            over_cpu = limits.time_limit is not None and cpu > limits.time_limit
            over_wall = wall_cap is not None and time.monotonic() - start > wall_cap
            if limits.memory_limit is not None and rss > limits.memory_limit:
                hit = "memory"
            elif over_cpu:
                hit = "time"
            elif over_wall:
                hit = "wall"
            if hit is not None:
                _kill_tree(proc.pid)
        time.sleep(limits.poll_interval)
