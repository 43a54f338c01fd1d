#!/usr/bin/env bash
# Reproduce the paper's Section V (Table 1, PAR10 figure) with artiplan, ENHSP and Kairos.
#
#   benchmarks/bench_suite.sh [TIME_LIMIT_S] [JOBS] [PLANNERS]
#
# Resumable: run it again after a kill and it only runs what is missing from the results file.
# Environment: SCHEDULER=tcp://host:8786 runs the jobs on a Dask cluster instead of locally;
# MEMORY_LIMIT (MiB, default 8192 as in the paper).
set -euo pipefail
cd "$(dirname "$0")/.."
LIMIT="${1:-60}"
JOBS="${2:-1}"
PLANNERS="${3:-artiplan,enhsp,kairos}"
PY="${PYTHON:-.venv/bin/python}"
SUITE=benchmarks/suite
OUT=benchmarks/results.jsonl

[ -f "$SUITE/suite.json" ] || "$PY" -m artiplan suite "$SUITE"
"$PY" -m artiplan bench "$SUITE" --planners "$PLANNERS" --time-limit "$LIMIT" \
    --memory-limit "${MEMORY_LIMIT:-8192}" --jobs "$JOBS" --out "$OUT" \
    ${SCHEDULER:+--scheduler "$SCHEDULER"}
"$PY" -m artiplan report "$OUT" -o benchmarks/report
