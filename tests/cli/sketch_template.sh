#!/usr/bin/env bash
# examples/sketch-template, as a student uses it: installs the build tree into a scratch prefix (as
# tests/install/install_test.sh), copies the template out of the source tree, configures it with find_package(tessera)
# against the prefix, builds it with tessera_add_sketch, and runs the program with the runner's flags: a headless GIF
# and a PNG, the same bytes for --threads 1 and 2, usage errors exit 2, no display exits 1 suggesting --headless.
# Usage: sketch_template.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR
set -euo pipefail
build=$1 source=$2 scratch=$3
fail() { echo "sketch_template.sh: $*"; exit 1; }
rm -rf "$scratch" && mkdir -p "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
cp -r "$source/examples/sketch-template" "$scratch/my_sketch"
cmake -S "$scratch/my_sketch" -B "$scratch/my_sketch/build" -G Ninja -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/my_sketch/build" >/dev/null
program=$scratch/my_sketch/build/my_sketch
[ -x "$program" ] || fail "tessera_add_sketch built no program"

cd "$scratch"
"$program" --help | grep -q -- "--headless" || fail "--help lacks the runner's flags"
stats=$("$program" --headless --seconds 0.5 -o ball.gif --seed 3 --stats)
grep -qx "frames=30" <<<"$stats" || fail "0.5 s at 60 fps is not 30 frames: $stats"
grep -qx "width=400" <<<"$stats" || fail "the sketch is not 400 wide: $stats"
[ -s ball.gif ] || fail "no ball.gif"
"$program" --headless --frames 10 -o t1.png --threads 1 --seed 3
"$program" --headless --frames 10 -o t2.png --threads 2 --seed 3
cmp -s t1.png t2.png || fail "the picture depends on --threads"
"$program" --headless --frames 10 -o s4.png --seed 4
cmp -s t1.png s4.png && fail "--seed does not change random()"
printf '5 mouse_move 40 40\n5 mouse_press left\n' >click.txt
"$program" --headless --frames 6 --input click.txt -o click.png --seed 3
cmp -s t1.png click.png && fail "the scripted click changed nothing"

set +e
"$program" --frames 0 --headless -o x.png 2>err; status=$?
[ $status -eq 2 ] || fail "--frames 0 exited $status, expected 2"
env -u DISPLAY -u WAYLAND_DISPLAY "$program" --frames 2 2>err; status=$?
set -e
[ $status -eq 1 ] || fail "a window without a display exited $status, expected 1"
grep -q "my_sketch: error: .*--headless" err || fail "unclear no-display error: $(cat err)"
echo "sketch_template.sh: ok"
