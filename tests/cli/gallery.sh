#!/usr/bin/env bash
# tessera gallery / demo and the shared data: --data DIR first, then $TESSERA_DATA, then $TESSERA_SHARED_DATA, then
# ./shared/data, ../shared/data, shared/data above the executable and the build's folder. A missing data file draws a
# stand-in, says so on stderr and in the picture's caption (index.html), and counts in --stats' stand_ins.
set -euo pipefail
tessera=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"

fail() { echo "gallery.sh: $*"; exit 1; }

real=${TESSERA_SHARED_DATA:-}
empty=$scratch/empty-data
mkdir -p "$empty"

# Example 42 reads bezier/teapot.bpt; without it a dome of 4 patches stands in.
gallery42() {  # gallery42 OUT [options...]: runs `tessera gallery --only 42 -o OUT --stats` without the variables
  local out=$1; shift
  env -u TESSERA_DATA -u TESSERA_SHARED_DATA "$tessera" gallery --only 42 -o "$out" --stats "$@" \
    >"$out.stdout" 2>"$out.stderr"
}
expect_stand_in() {  # expect_stand_in OUT WHERE: a warning on stderr naming the file and WHERE, a STAND-IN caption
  grep -q "warning: shared data file bezier/teapot.bpt" "$1.stderr" || fail "$1: no stand-in warning: $(cat "$1.stderr")"
  grep -qF -- "$2" "$1.stderr" || fail "$1: the warning does not name '$2': $(cat "$1.stderr")"
  grep -qx "stand_ins=1" "$1.stdout" || fail "$1: --stats lacks stand_ins=1: $(cat "$1.stdout")"
  grep -q "STAND-IN (shared data not found; drawn instead of the Utah teapot: a dome of 4 patches)" "$1/index.html" || fail "$1: caption lacks STAND-IN"
  [ -s "$1/42_bezier_patches.png" ] || fail "$1: no picture"
}
expect_real() {  # expect_real OUT: no warning, the teapot's caption
  [ ! -s "$1.stderr" ] || fail "$1: stderr is not empty: $(cat "$1.stderr")"
  grep -qx "stand_ins=0" "$1.stdout" || fail "$1: --stats lacks stand_ins=0: $(cat "$1.stdout")"
  grep -qx "pictures=1" "$1.stdout" || fail "$1: --stats lacks pictures=1: $(cat "$1.stdout")"
  grep -qx "total_s=.*" "$1.stdout" || fail "$1: --stats lacks total_s: $(cat "$1.stdout")"
  grep -q "The Utah teapot: 32 bicubic patches" "$1/index.html" || fail "$1: caption is not the teapot's"
  ! grep -q "STAND-IN" "$1/index.html" || fail "$1: a STAND-IN caption with the data present"
}

# --data: an empty folder gives a stand-in, reported; the real folder gives the teapot.
gallery42 "$scratch/option-empty" --data "$empty"
expect_stand_in "$scratch/option-empty" "$empty (from --data)"
if [ -f "$real/bezier/teapot.bpt" ]; then
  gallery42 "$scratch/option-real" --data "$real"
  expect_real "$scratch/option-real"
  # --data wins over the environment.
  TESSERA_DATA=$empty "$tessera" gallery --only 42 -o "$scratch/option-wins" --data "$real" --stats \
    >"$scratch/option-wins.stdout" 2>"$scratch/option-wins.stderr"
  expect_real "$scratch/option-wins"
fi

# The environment: TESSERA_DATA, then TESSERA_SHARED_DATA (kept working).
out=$scratch/env-short
TESSERA_DATA=$empty TESSERA_SHARED_DATA=/nonexistent "$tessera" gallery --only 42 -o "$out" --stats \
  >"$out.stdout" 2>"$out.stderr"
expect_stand_in "$out" "(from TESSERA_DATA)"
out=$scratch/env-long
env -u TESSERA_DATA TESSERA_SHARED_DATA="$empty" "$tessera" gallery --only 42 -o "$out" --stats \
  >"$out.stdout" 2>"$out.stderr"
expect_stand_in "$out" "(from TESSERA_SHARED_DATA)"

# The documented folders, relative to the current folder: ./shared/data before ../shared/data before the rest (here
# both are empty, so the warning names the one chosen).
mkdir -p "$scratch/here/shared/data" "$scratch/up/shared/data" "$scratch/up/main"
(cd "$scratch/here" && gallery42 "$scratch/cwd-here")
expect_stand_in "$scratch/cwd-here" "(from ./shared/data)"
(cd "$scratch/up/main" && gallery42 "$scratch/cwd-up")
expect_stand_in "$scratch/cwd-up" "(from ../shared/data)"
# Neither: shared/data above the executable, or the build's folder (the real data when the build has it).
if [ -f "$real/bezier/teapot.bpt" ]; then
  mkdir -p "$scratch/nowhere"
  (cd "$scratch/nowhere" && gallery42 "$scratch/cwd-none")
  expect_real "$scratch/cwd-none"
fi

# Without --stats the summary line mentions the stand-ins too.
summary=$("$tessera" gallery --only 42 -o "$scratch/summary" --data "$empty" 2>/dev/null)
grep -q "1 stand-in(s) for missing shared data" <<<"$summary" || fail "summary lacks the stand-in note: $summary"

# --data must name a folder: a usage error (exit 2), for both commands.
for command in gallery demo; do
  status=0
  "$tessera" $command -o "$scratch/bad" --data "$scratch/no-such-folder" >/dev/null 2>"$scratch/bad.stderr" || status=$?
  [ "$status" = 2 ] || fail "$command --data with a missing folder: exit $status, expected 2"
  grep -q "tessera: error" "$scratch/bad.stderr" || fail "$command --data: $(cat "$scratch/bad.stderr")"
  "$tessera" $command --help | grep -q -- "--data" || fail "$command --help lacks --data"
done
[ ! -e "$scratch/bad" ] || fail "a usage error left an output folder"

# --only must select something: a prefix that matches no example is a usage error naming the examples' numbers.
status=0
"$tessera" gallery --only 99 -o "$scratch/none" >/dev/null 2>"$scratch/none.stderr" || status=$?
[ "$status" = 2 ] || fail "--only 99: exit $status, expected 2"
grep -q "no example's name starts with '99'" "$scratch/none.stderr" || fail "--only 99: $(cat "$scratch/none.stderr")"
[ ! -e "$scratch/none" ] || fail "--only 99 left an output folder"

# --progress plain: one line when the gallery starts and one when it ends, on stderr (for logs).
"$tessera" gallery --only 01 -o "$scratch/progress" --progress plain --data "$empty" >/dev/null 2>"$scratch/progress.stderr"
grep -q "^gallery: started" "$scratch/progress.stderr" || fail "no plain progress: $(cat "$scratch/progress.stderr")"
grep -q "^gallery: done" "$scratch/progress.stderr" || fail "no plain progress end: $(cat "$scratch/progress.stderr")"

echo "gallery.sh: ok"
