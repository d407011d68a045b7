#!/usr/bin/env bash
# The CLI's common contract: help lists every command, usage errors exit 2, runtime errors exit 1 with
# "tessera: error:", and the gallery writes pictures plus an index.html.
set -euo pipefail
tessera=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"

help=$("$tessera" --help)
for command in demo gallery canvas color mesh curve patch fractal; do
  grep -q "^  $command" <<<"$help" || { echo "--help does not list '$command'"; exit 1; }
done
"$tessera" --version | grep -q '^tessera '

expect_exit() {  # expect_exit CODE PATTERN COMMAND...: runs COMMAND, checks its exit code and that stderr matches
  local code=$1 pattern=$2; shift 2
  local status=0
  "$@" 2>"$scratch/stderr" >/dev/null || status=$?
  [ "$status" -eq "$code" ] || { echo "expected exit $code, got $status: $*"; cat "$scratch/stderr"; exit 1; }
  grep -q -- "$pattern" "$scratch/stderr" || { echo "stderr lacks '$pattern': $*"; cat "$scratch/stderr"; exit 1; }
}
expect_exit 2 "" "$tessera"
expect_exit 2 "" "$tessera" no-such-command
expect_exit 2 "" "$tessera" gallery --no-such-option
expect_exit 2 "" "$tessera" gallery --threads -3
# Floating-point options refuse NaN and infinities (CLI11's range checks let NaN through).
expect_exit 2 "expected a finite number, got 'nan'" "$tessera" volume render sphere:8 -o "$scratch/nan.png" --fovy nan
expect_exit 2 "expected a finite number, got 'inf'" "$tessera" volume render sphere:8 -o "$scratch/inf.png" --far inf
[ ! -e "$scratch/nan.png" ] && [ ! -e "$scratch/inf.png" ] || { echo "a picture was written"; exit 1; }
expect_exit 1 "tessera: error:" "$tessera" gallery -o /proc/forbidden/gallery

"$tessera" gallery --only 01 -o "$scratch/gallery" >/dev/null
[ -s "$scratch/gallery/index.html" ] || { echo "no index.html"; exit 1; }
ls "$scratch"/gallery/*.png >/dev/null
echo "cli basics: ok"
