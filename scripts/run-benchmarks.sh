#!/usr/bin/env bash
# Runs every benchmark program of a build folder and prints their tables (and the peers' figures in the same run),
# then the ray tracer against POV-Ray. Without a display the programs run under a virtual X server when xvfb-run is
# there: Debian's VTK needs one for its volume ray-cast mapper.
set -euo pipefail
build=${1:-build/bench}
x=()
if [ -z "${DISPLAY:-}" ] && command -v xvfb-run >/dev/null; then x=(xvfb-run -a); fi
for b in "$build"/bench/bench_*; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  "${x[@]}" "$b" --benchmark_counters_tabular=true
done
echo "== raytrace vs POV-Ray"
/usr/bin/python3 "$(dirname "$0")/../bench/peers/raytrace_povray.py" "$build/apps/tessera/tessera" --threads 1
