#!/usr/bin/env bash
# ENHSP with the two forms of the wrap-around events (benchmarks/results/encoding.md):
#   assign (what the generator writes): back-to-zero -> 0, back-to-360 -> 359.99
#   shift: back-to-zero decreases by 360, back-to-360 increases by 360
# Usage: bash benchmarks/encoding_wrap_variants.sh [TIMEOUT_S]   (about 10 min worst case)
set -euo pipefail
T=${1:-20}
ROOT=$(cd "$(dirname "$0")/.." && pwd)
JAR=$("$ROOT/.venv/bin/python" -c 'import importlib.util,os;print(os.path.join(list(importlib.util.find_spec("up_enhsp").submodule_search_locations)[0],"ENHSP","enhsp.jar"))')
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
"$ROOT/.venv/bin/artiplan" suite "$TMP/s" >/dev/null
for m in ng ucm-0.5 uacm-0.5; do
  sed 's/:effect (assign (angle ?l ?p) 0))/:effect (decrease (angle ?l ?p) 360))/; s/:effect (assign (angle ?l ?p) 359.99))/:effect (increase (angle ?l ?p) 360))/' \
    "$TMP/s/$m/domain.pddl" > "$TMP/$m-shift.pddl"
  for p in 3-1 3-2 3-3 3-4 3-5 4-1 4-2 4-3 4-4 4-5; do
    for v in assign shift; do
      d="$TMP/s/$m/domain.pddl"; [ "$v" = shift ] && d="$TMP/$m-shift.pddl"
      s=$(date +%s.%N)
      r=$(timeout "$T" java -jar "$JAR" -o "$d" -f "$TMP/s/$m/p$p.pddl" 2>&1 | grep -c "Problem Solved" || true)
      e=$(date +%s.%N)
      echo "$m p$p $v solved=$r wall=$(echo "$e - $s" | bc)"
    done
  done
done
