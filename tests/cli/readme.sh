#!/usr/bin/env bash
# The README's examples, run as written: every command line of its ```sh blocks that calls `tessera`, from a folder
# laid out as a fresh clone (the source tree's files, ../shared/data beside it when the shared data sets are there).
# A line that needs the shared data is skipped, and said so, when they are not there. A line that fails fails the test.
# $1 = the tessera binary, $2 = a scratch folder.
set -euo pipefail
tessera=$1 dir=$2
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
rm -rf "$dir"
mkdir -p "$dir/bin" "$dir/clone"
ln -s "$tessera" "$dir/bin/tessera"
# The clone: the tracked folders a README line may name (read-only use), and room for its outputs.
for entry in examples tests scenes; do ln -s "$source_dir/$entry" "$dir/clone/$entry"; done
have_data=0
if [ -n "${TESSERA_SHARED_DATA:-}" ] && [ -d "$TESSERA_SHARED_DATA" ]; then
  mkdir -p "$dir/shared" && ln -s "$TESSERA_SHARED_DATA" "$dir/shared/data" && have_data=1
fi

# The lines: inside ```sh fences, not comments, calling tessera (directly or at the end of a pipe).
mapfile -t lines < <(awk '/^```sh/{f=1; next} /^```/{f=0} f' "$source_dir/README.md" |
                     sed -e 's/[[:space:]]#.*$//' | grep -E '(^|\|[[:space:]]*)tessera ' || true)
[ ${#lines[@]} -ge 5 ] || { echo "FAIL: found only ${#lines[@]} tessera lines in README.md"; exit 1; }

ran=0 skipped=0
cd "$dir/clone"
for line in "${lines[@]}"; do
  if [[ $line == *../shared/data* && $have_data -eq 0 ]]; then
    echo "skipped (no shared data in TESSERA_SHARED_DATA): $line"
    skipped=$((skipped + 1))
    continue
  fi
  if ! PATH="$dir/bin:$PATH" bash -c "set -o pipefail; $line" >"$dir/out.txt" 2>"$dir/err.txt"; then
    echo "FAIL: the README's example failed: $line"
    cat "$dir/err.txt"
    exit 1
  fi
  ran=$((ran + 1))
done
echo "readme examples: $ran ran, $skipped skipped"
