#!/usr/bin/env bash
# tessera view in a real window: under xvfb-run, `tessera view cube.obj --window` opens an X window; xdotool sends a
# real left drag (arcball orbit), a key (2: flat shading), a right drag (pan) and a wheel turn (zoom). After each step
# ImageMagick's `import` grabs the window, and the grab is compared with the headless render of the same state (an
# input script with the same pointer positions, buttons, keys and wheel steps): within 1/255 on at least 99% of the
# pixels (PIL and numpy, independent of Tessera). The arcball's rotation depends only on where a drag starts and ends
# (Shoemake), so the motion events the X server coalesces or splits do not matter. The status line is off in both
# (its frame time is the window's own). Skips (77) without xvfb-run, xdotool, import, PIL/numpy or an SDL2 build.
set -euo pipefail
tessera=$1 scratch=$2
data="$(cd "$(dirname "$0")/../data" && pwd)"
fail() { echo "view_window.sh: $*"; exit 1; }
. "$(dirname "$0")/window_lib.sh"

if [ "${3:-}" != --inside ]; then
  window_prepare "$scratch"
  cp "$data/cube.obj" "$scratch/cube.obj"
  window_enter_x "$tessera" "$scratch" view "$scratch/cube.obj" --window --frames 1
fi

# ---- inside the X server ------------------------------------------------------------------------------------------
cd "$scratch"
script=""
# The headless picture of the state reached so far: every event of the window so far, at frame 1.
headless() {  # NAME
  printf '%b' "$script" > "$1.txt"
  "$tessera" view cube.obj --headless --size 400x300 --no-status --input "$1.txt" -o "$1-headless.png"
}
grab() { sleep 1; import -window "$wid" "$1-window.png"; }
compare() { compare_grab "$1-window.png" "$1-headless.png"; }  # NAME
step() {  # NAME: grab the window, render the script headless, compare
  grab "$1"
  headless "$1"
  compare "$1" || fail "$1: the window differs from the headless render"
}

"$tessera" view cube.obj --window --size 400x300 --no-status >window.out 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
wid=$(timeout 20 xdotool search --sync --name "tessera view cube.obj" | head -1)
[ -n "$wid" ] || fail "no window appeared: $(cat window.out)"
xdotool getwindowgeometry "$wid" | grep -q "Geometry: 400x300" || fail "the window is not 400x300"
step home

# A left drag: the arcball turns the cube.
xdotool mousemove --window "$wid" 200 150 mousedown 1
xdotool mousemove --window "$wid" 230 140
xdotool mousemove --window "$wid" 270 110 mouseup 1
script+="1 mouse_move 200 150\n1 mouse_press left\n1 mouse_move 270 110\n1 mouse_release left\n"
step orbit
cmp -s home-headless.png orbit-headless.png && fail "the drag did not turn the cube"

# A key: 2 is flat shading.
xdotool windowfocus --sync "$wid"
xdotool key 2
script+="1 key_press 2\n"
step flat

# A right drag pans, the wheel zooms (one step toward the screen: closer).
xdotool mousemove --window "$wid" 100 100 mousedown 3
xdotool mousemove --window "$wid" 140 120 mouseup 3
script+="1 mouse_move 100 100\n1 mouse_press right\n1 mouse_move 140 120\n1 mouse_release right\n"
xdotool click 4
script+="1 mouse_wheel -1\n"
step pan_zoom

# Escape closes the window and ends the run.
xdotool key Escape
for _ in $(seq 50); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
kill -0 $pid 2>/dev/null && fail "Escape did not close the viewer"
wait $pid || fail "the viewer exited with an error: $(cat window.out)"
trap - EXIT

# Live shader editing: the window draws the cube through a GLSL program and compiles it again when the file changes
# on disk; a broken edit keeps the last good program.
printf 'void main() { gl_Position = ftransform(); }\n' > paint.vert
printf 'void main() { gl_FragColor = vec4(1.0, 0.0, 0.0, 1.0); }\n' > paint.frag
"$tessera" view cube.obj --window --size 400x300 --no-status --vertex-shader paint.vert --fragment-shader paint.frag \
  >shader.out 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
wid=$(timeout 20 xdotool search --sync --name "tessera view cube.obj" | head -1)
[ -n "$wid" ] || fail "no shader window appeared: $(cat shader.out)"
center() {  # GRAB: the color at the window's center
  /usr/bin/python3 -c "import sys; from PIL import Image; print('%d,%d,%d' % Image.open(sys.argv[1]).convert('RGB').getpixel((200, 150)))" "$1"
}
grab red
[ "$(center red-window.png)" = "255,0,0" ] || fail "the program's red is not drawn: $(center red-window.png)"
printf 'void main() { gl_FragColor = vec4(0.0, 1.0, 0.0, 1.0); }\n' > paint.frag
grab green
[ "$(center green-window.png)" = "0,255,0" ] || fail "the edited shader was not reloaded: $(center green-window.png)"
printf 'void main() { gl_FragColor = 1.0; }\n' > paint.frag
grab broken
[ "$(center broken-window.png)" = "0,255,0" ] || fail "a broken edit changed the picture: $(center broken-window.png)"
xdotool windowfocus --sync "$wid"
xdotool key Escape
for _ in $(seq 50); do kill -0 $pid 2>/dev/null || break; sleep 0.1; done
wait $pid || fail "the shader viewer exited with an error: $(cat shader.out)"
trap - EXIT
echo "view_window.sh: the window matched the headless renders; shader edits were reloaded"
