#!/usr/bin/env bash
# tessera sketch, headless: --list; the same bytes for --threads 1 and 2 (a PNG sequence and a GIF); the GIF's
# structure read back by PIL (frame count, size, delays); --stats; the picture of a scripted state checked pixel by
# pixel against the notes' rectangle (PIL/numpy); usage errors exit 2, runtime errors exit 1 with no output file; with
# no display, --window fails with a clear error that suggests --headless (exit 1).
set -euo pipefail
tessera=$1 scratch=$2
python=/usr/bin/python3
rm -rf "$scratch" && mkdir -p "$scratch"
fail() { echo "sketch_headless.sh: $*"; exit 1; }
have_pil=0
"$python" -c 'import PIL, numpy' 2>/dev/null && have_pil=1

# --list names each built-in with a line.
list=$("$tessera" sketch --list)
grep -q "^pink_square  *The notes' pink" <<<"$list" || fail "--list lacks pink_square: $list"
grep -q "^rotating_cube " <<<"$list" || fail "--list lacks rotating_cube: $list"

# Deterministic: the same frames byte for byte with 1 and 2 threads, in 2D and 3D.
for name in pink_square rotating_cube; do
  for t in 1 2; do
    "$tessera" sketch $name --headless --demo --frames 20 --threads $t -o "$scratch/$name-t$t/" --quiet
    "$tessera" sketch $name --headless --demo --frames 20 --threads $t -o "$scratch/$name-t$t.gif" --quiet
  done
  [ "$(ls "$scratch/$name-t1" | wc -l)" = 20 ] || fail "$name: expected 20 PNG frames"
  for f in "$scratch/$name-t1"/*.png; do
    cmp -s "$f" "$scratch/$name-t2/$(basename "$f")" || fail "$name: $(basename "$f") differs between --threads 1 and 2"
  done
  cmp -s "$scratch/$name-t1.gif" "$scratch/$name-t2.gif" || fail "$name: the GIF differs between --threads 1 and 2"
  cmp -s "$scratch/$name-t1/frame-0000.png" "$scratch/$name-t1/frame-0019.png" && fail "$name: the frames do not move"
done

# --stats: the vocabulary's counts and phases.
stats=$("$tessera" sketch pink_square --headless --frames 5 -o "$scratch/five.png" --stats)
for key in width=400 height=400 pixels=160000 frames=5 draws=5; do
  grep -qx "$key" <<<"$stats" || fail "--stats lacks $key: $stats"
done
for key in compute_s write_s total_s; do grep -q "^$key=" <<<"$stats" || fail "--stats lacks $key"; done

# A scripted state, checked against the notes' rectangle: rect(mouseX - 25, mouseY - 25, 50, 50) at (300, 60) covers
# x in [275, 325), y in [35, 85), pink (255, 150, 150) on white; --size 500x300 replaces size(400, 400).
printf '# the pointer goes to (300, 60)\n2 mouse_move 300 60\n' >"$scratch/move.txt"
"$tessera" sketch pink_square --headless --frames 3 --input "$scratch/move.txt" --size 500x300 -o "$scratch/move.png"
if [ $have_pil = 1 ]; then
  "$python" - "$scratch/move.png" <<'PY' || fail "move.png is not the pink square at (300, 60)"
import sys
import numpy as np
from PIL import Image
a = np.asarray(Image.open(sys.argv[1]).convert("RGB")).astype(int)
want = np.full((300, 500, 3), 255)
want[35:85, 275:325] = (255, 150, 150)
sys.exit(0 if a.shape == want.shape and (a == want).all() else 1)
PY
  # The GIF: 60 fps sketch frames kept every second frame (GIF delays are whole centiseconds: 30 fps is 3, 3, 4 cs).
  "$python" - "$scratch/pink_square-t1.gif" <<'PY' || fail "the GIF's structure is wrong"
import sys
from PIL import Image
im = Image.open(sys.argv[1])
delays = []
for i in range(im.n_frames):
    im.seek(i)
    delays.append(im.info["duration"])
print("gif:", im.n_frames, "frames", im.size, "delays", delays[:6])
sys.exit(0 if im.n_frames == 10 and im.size == (400, 400) and delays[:6] == [30, 30, 40, 30, 30, 40] else 1)
PY
fi

# MP4 through ffmpeg: every frame at the sketch's rate (ffprobe counts them).
if command -v ffmpeg >/dev/null && command -v ffprobe >/dev/null; then
  "$tessera" sketch rotating_cube --headless --frames 12 --size 128x96 -o "$scratch/cube.mp4" --quiet
  probe=$(ffprobe -v error -count_frames -select_streams v:0 \
            -show_entries stream=nb_read_frames,width,height,r_frame_rate -of csv=p=0 "$scratch/cube.mp4")
  [ "$probe" = "128,96,60/1,12" ] || fail "cube.mp4 is not 12 frames of 128x96 at 60 fps: $probe"
fi

# A sketch with no script runs its default length (the sketch's demo length) and stops there.
"$tessera" sketch rotating_cube --headless -o "$scratch/cube/" --quiet --size 64x64
[ "$(ls "$scratch/cube" | wc -l)" = 60 ] || fail "rotating_cube's default run is not 60 frames"

# Usage errors: exit 2.
expect_usage() {
  set +e
  "$tessera" sketch "$@" >"$scratch/out" 2>&1
  local status=$?
  set -e
  [ $status -eq 2 ] || fail "'sketch $*' exited $status, expected 2: $(cat "$scratch/out")"
}
expect_usage no_such_sketch --headless
expect_usage
expect_usage pink_square --frames 0
expect_usage pink_square --frames 2 --seconds 1
expect_usage pink_square --size 400
expect_usage pink_square --window --headless
expect_usage pink_square --fps 0

# Runtime errors: exit 1, a message naming the file and line, no output file.
printf '1 mouse_move 10 10\n2 mouse_hop 3 4\n' >"$scratch/bad.txt"
set +e
"$tessera" sketch pink_square --headless --input "$scratch/bad.txt" -o "$scratch/bad.gif" 2>"$scratch/err"
status=$?
set -e
[ $status -eq 1 ] || fail "a bad input script exited $status, expected 1"
grep -q "bad.txt line 2: unknown event 'mouse_hop'" "$scratch/err" || fail "unclear script error: $(cat "$scratch/err")"
[ ! -e "$scratch/bad.gif" ] || fail "a failed run left bad.gif"

# No display: a clear error suggesting --headless, exit 1.
set +e
env -u DISPLAY -u WAYLAND_DISPLAY "$tessera" sketch pink_square --window --frames 2 2>"$scratch/err"
status=$?
set -e
[ $status -eq 1 ] || fail "--window without a display exited $status, expected 1"
grep -q "^tessera: error: .*run with --headless" "$scratch/err" || fail "unclear no-display error: $(cat "$scratch/err")"
# Without -o and without --headless the sketch opens a window, so the same error.
set +e
env -u DISPLAY -u WAYLAND_DISPLAY "$tessera" sketch pink_square 2>"$scratch/err"
status=$?
set -e
[ $status -eq 1 ] || fail "a window run without a display exited $status, expected 1"
echo "sketch_headless.sh: ok"
