#!/usr/bin/env bash
# A fuzzing campaign beyond CI's 10 seconds per target: runs every libFuzzer target of the clang build (make asan)
# for SECONDS each, JOBS at a time, from the seeds in fuzz/corpus/<name>/ plus what earlier runs found (kept in
# build/asan/fuzz/fuzz-corpus/<name>/), and prints one line per target: CPU seconds, executions, coverage, findings.
#
#   scripts/fuzz-campaign.sh SECONDS [TARGET...]     (JOBS=2 by default; TARGET names as in fuzz/, e.g. obj scene)
#
# A finding is written to build/asan/fuzz/fuzz-artifacts/<name>-crash-… (or leak-, timeout-, oom-); replay it with
# build/asan/fuzz/fuzz_<name> FILE, fix the bug, and add the file to fuzz/corpus/<name>/. To fold what a campaign found
# into the seeds, minimized: build/asan/fuzz/fuzz_<name> -merge=1 fuzz/corpus/<name> build/asan/fuzz/fuzz-corpus/<name>
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: fuzz-campaign.sh SECONDS [TARGET...]}
shift
bin=build/asan/fuzz
[ -d "$bin" ] || { echo "fuzz-campaign: no $bin: build it first (make asan)" >&2; exit 2; }
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in "$bin"/fuzz_*; do [ -x "$f" ] && targets+=("${f##*/fuzz_}"); done
fi
logs=$(mktemp -d)
export ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$PWD/cmake/lsan-suppressions.txt
run_one() {
  local name=$1
  mkdir -p "$bin/fuzz-corpus/$name" "$bin/fuzz-artifacts"
  # CPU seconds (user + system) are what the campaign reports: on a shared machine they are less than the wall time.
  local TIMEFORMAT="cpu_seconds %U %S"
  { time "$bin/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2560 -print_final_stats=1 \
      -artifact_prefix="$bin/fuzz-artifacts/$name-" "$bin/fuzz-corpus/$name" "fuzz/corpus/$name" >"$logs/$name" 2>&1 \
      || echo "FINDING" >>"$logs/$name"; } 2>"$logs/$name.time"
}
export -f run_one
export bin seconds logs
printf '%s\n' "${targets[@]}" | xargs -P "${JOBS:-2}" -I{} bash -c 'run_one {}'
printf '%-16s %11s %12s %8s %8s  %s\n' target cpu_seconds executions cov ft findings
for name in "${targets[@]}"; do
  log=$logs/$name
  stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  finding=none
  grep -q FINDING "$log" && finding="$(grep -m1 -E 'ERROR|runtime error|deadly signal' "$log" || echo 'see log') ($log)"
  cpu=$(awk '/^cpu_seconds/ { printf "%.0f", $2 + $3 }' "$log.time")
  printf '%-16s %11s %12s %8s %8s  %s\n' "$name" "${cpu:-?}" "$(stat number_of_executed_units)" \
    "${cov:-?}" "${ft:-?}" "$finding"
done
