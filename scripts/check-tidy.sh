#!/usr/bin/env bash
# Runs clang-tidy (the checks of .clang-tidy) on the library's and the command's sources and fails (exit 1) on a
# finding that .clang-tidy-baseline does not list: the findings the tree had when the check was introduced are listed
# there per file and check, to be fixed over time; a new one fails `make test`.
#   scripts/check-tidy.sh BUILD_DIR            BUILD_DIR has compile_commands.json (the clang build: build/asan)
#   scripts/check-tidy.sh BUILD_DIR --update   rewrite the baseline from the current findings
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: check-tidy.sh BUILD_DIR [--update]}
tidy=$(command -v clang-tidy-14 || command -v clang-tidy || true)
[ -n "$tidy" ] || { echo "check-tidy: clang-tidy not found (scripts/install-deps.sh installs it)" >&2; exit 2; }
[ -f "$build/compile_commands.json" ] || { echo "check-tidy: no $build/compile_commands.json (configure it first)" >&2; exit 2; }
found=$(mktemp) out=$(mktemp)
trap 'rm -f "$found" "$out"' EXIT
# The sources this build compiles (a source of a disabled option, such as the window without SDL2, has no command).
mapfile -t files < <(git ls-files 'libs/*/src/*.cpp' 'apps/*.cpp' |
  while read -r f; do grep -qF "\"file\": \"$PWD/$f\"" "$build/compile_commands.json" && echo "$f"; done)
# One file per clang-tidy run, as many at once as there are cores. A file clang cannot compile fails the check rather
# than passing it unread.
if ! printf '%s\n' "${files[@]}" |
  xargs -P "$(nproc)" -n 1 "$tidy" -p "$build" --quiet --header-filter="^$PWD/(libs|apps)/" >"$out" 2>/dev/null; then
  echo "check-tidy: clang-tidy could not check every file:" >&2
  grep -m 20 ': error: ' "$out" >&2 || true
  exit 2
fi
# Findings in Tessera's own headers count once, however many sources include them.
sed -n "s|^$PWD/\([^:]*\):\([0-9]*:[0-9]*\): warning: .* \[\([a-z0-9.,-]*\)\]$|\1 \3 \2|p" "$out" | sort -u |
  awk '{ n[$1 " " $2]++ } END { for (k in n) print k, n[k] }' | sort >"$found"
if [ "${2:-}" = "--update" ]; then
  cp "$found" .clang-tidy-baseline
  echo "check-tidy: baseline rewritten ($(awk '{ s += $3 } END { print s + 0 }' .clang-tidy-baseline) findings)"
  exit 0
fi
# A (file, check) pair with more findings than the baseline allows is new.
new=$(awk 'NR == FNR { allowed[$1 " " $2] = $3; next } $3 > allowed[$1 " " $2] + 0 { print "  " $1 ": " $3 " " $2 \
  " finding(s), the baseline allows " allowed[$1 " " $2] + 0 }' .clang-tidy-baseline "$found")
if [ -n "$new" ]; then
  echo "check-tidy: new clang-tidy findings (run clang-tidy -p $build FILE to see them; fix them):" >&2
  echo "$new" >&2
  exit 1
fi
echo "check-tidy: no new findings ($(awk '{ s += $3 } END { print s + 0 }' "$found") listed in .clang-tidy-baseline remain)"
