#!/usr/bin/env bash
# Runs every benchmark program of a build folder and prints their tables (and the peers' figures in the same run).
set -euo pipefail
build=${1:-build/bench}
for b in "$build"/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "$b" --benchmark_counters_tabular=true
done
