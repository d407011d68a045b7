#!/usr/bin/env bash
# tessera sketch --window, for real: under xvfb-run, `tessera sketch pink_square --window` opens an X window; xdotool
# moves the real pointer into it, drags, types a key, hands the focus to another window and back, resizes the window
# (the sketch keeps its 400x400 and is drawn scaled to fit, letterboxed), and a WM_DELETE_WINDOW message closes it.
# After each step ImageMagick's `import` grabs the window, and the grab is compared with the headless render of the
# same state (a script with the same mouse position, button and key): within 1/255 on at least 99% of the pixels
# (PIL and numpy, independent of Tessera). Skips (77) without xvfb-run, xdotool, import, PIL or an SDL2 build.
set -euo pipefail
tessera=$1 scratch=$2
python=/usr/bin/python3
fail() { echo "sketch_window.sh: $*"; exit 1; }
. "$(dirname "$0")/window_lib.sh"

if [ "${3:-}" != --inside ]; then
  window_prepare "$scratch"
  window_enter_x "$tessera" "$scratch" sketch pink_square --window --frames 1
fi

# ---- inside the X server ------------------------------------------------------------------------------------------
# The headless picture of a state: `script` lines at frame 1, one frame, the last frame as PNG.
headless() {  # NAME SCRIPT
  printf '%b' "$2" >"$scratch/$1.txt"
  "$tessera" sketch pink_square --headless --frames 1 --input "$scratch/$1.txt" -o "$scratch/$1-headless.png"
}
grab() { sleep 0.6; import -window "$wid" "$scratch/$1-window.png"; }
compare() { compare_grab "$scratch/$1-window.png" "$scratch/$1-headless.png" "${@:2}"; }  # NAME [SCALE OX OY]

"$tessera" sketch pink_square --window --seconds 60 >"$scratch/window.out" 2>&1 &
pid=$!
wid=$(timeout 20 xdotool search --sync --name "tessera sketch pink_square" | head -1)
[ -n "$wid" ] || fail "no window appeared: $(cat "$scratch/window.out")"
xdotool getwindowgeometry "$wid" | grep -q "Geometry: 400x400" || fail "the window is not 400x400"
start=$(date +%s)

# The pointer moves into the window: the square follows it.
xdotool mousemove --window "$wid" 100 80
grab move
headless move "1 mouse_move 100 80\n"
compare move || fail "move: the window differs from the headless render"

# A drag: the square darkens while the button is held.
xdotool mousedown 1
xdotool mousemove --window "$wid" 150 120
grab drag
headless drag "1 mouse_move 100 80\n1 mouse_press left\n1 mouse_move 150 120\n"
compare drag || fail "drag: the window differs from the headless render"
xdotool mouseup 1

# A key: 's' toggles the outline (typed through XTEST into the focused window).
xdotool windowfocus --sync "$wid"
xdotool key s
grab key
headless key "1 mouse_move 150 120\n1 key_press s\n"
compare key || fail "key: the window differs from the headless render"

# Focus loss: another window takes the focus; the sketch keeps running and takes it back.
"$tessera" sketch rotating_cube --window --seconds 30 --size 100x100 >/dev/null 2>&1 &
other_pid=$!
other=$(timeout 20 xdotool search --sync --pid $other_pid | head -1)
[ -n "$other" ] || fail "the second window did not appear"
xdotool windowfocus --sync "$other"
[ "$(xdotool getwindowfocus)" = "$other" ] || fail "the focus did not move to the second window"
sleep 0.5
kill -0 $pid || fail "the sketch ended when it lost the focus"
xdotool windowfocus --sync "$wid"
kill $other_pid 2>/dev/null || true  # it covers part of the first window
wait $other_pid 2>/dev/null || true
xdotool mousemove --window "$wid" 200 220
grab focus
headless focus "1 mouse_move 200 220\n1 key_press s\n"
compare focus || fail "after the focus came back: the window differs from the headless render"

# Resize to 800x600: the 400x400 sketch is drawn 1.5x (600x600) centered, black bars of 100 pixels left and right;
# the pointer at window (475, 375) is sketch pixel (250, 250).
xdotool windowsize --sync "$wid" 800 600
xdotool mousemove --window "$wid" 475 375
grab resize
headless resize "1 mouse_move 250 250\n1 key_press s\n"
file "$scratch/resize-window.png" | grep -q "800 x 600" || fail "the grab after the resize is not 800x600"
compare resize 1.5 100 0 || fail "resize: the window differs from the headless render scaled 1.5x"

# Close: the window manager's close message (WM_DELETE_WINDOW, as a title bar's close button sends) ends the run.
"$python" - "$wid" <<'PY'
import ctypes, ctypes.util, sys
x = ctypes.cdll.LoadLibrary(ctypes.util.find_library("X11"))
x.XOpenDisplay.restype = ctypes.c_void_p
x.XInternAtom.restype = ctypes.c_ulong
x.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
display = x.XOpenDisplay(None)
window = ctypes.c_ulong(int(sys.argv[1]))
protocols, delete = x.XInternAtom(display, b"WM_PROTOCOLS", 0), x.XInternAtom(display, b"WM_DELETE_WINDOW", 0)
class ClientMessage(ctypes.Structure):
    _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                ("display", ctypes.c_void_p), ("window", ctypes.c_ulong), ("message_type", ctypes.c_ulong),
                ("format", ctypes.c_int), ("data", ctypes.c_long * 5), ("pad", ctypes.c_long * 12)]
event = ClientMessage(type=33, send_event=1, display=display, window=window, message_type=protocols, format=32)
event.data[0], event.data[1] = delete, 0
x.XSendEvent.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_long, ctypes.c_void_p]
x.XSendEvent(display, window, 0, 0, ctypes.byref(event))
x.XFlush(display)
PY
status=0
wait $pid || status=$?
[ $status -eq 0 ] || fail "the sketch exited $status after the close message: $(cat "$scratch/window.out")"
[ $(( $(date +%s) - start )) -lt 50 ] || fail "the close message did not end the sketch (it ran to --seconds)"

# 3D in a window: the rotating cube's double-buffered frames reach the screen (its corner is the clear color
# (0.1, 0.1, 0.15) = (26, 26, 38), its center a face); Escape ends the run with status 0, as in Processing.
"$tessera" sketch rotating_cube --window --seconds 60 >"$scratch/cube.out" 2>&1 &
pid=$!
wid=$(timeout 20 xdotool search --sync --name "tessera sketch rotating_cube" | head -1)
[ -n "$wid" ] || fail "no 3D window appeared: $(cat "$scratch/cube.out")"
start=$(date +%s)
grab cube
"$python" - "$scratch/cube-window.png" <<'PY' || fail "the 3D window does not show the cube"
import sys
import numpy as np
from PIL import Image
a = np.asarray(Image.open(sys.argv[1]).convert("RGB")).astype(int)
print("cube window:", a.shape, "corner", a[0, 0], "center", a[200, 200])
sys.exit(0 if a.shape == (400, 400, 3) and (a[0, 0] == (26, 26, 38)).all() and (a[200, 200] != a[0, 0]).any() else 1)
PY
xdotool windowfocus --sync "$wid"
xdotool key Escape
status=0
wait $pid || status=$?
[ $status -eq 0 ] || fail "the 3D sketch exited $status after Escape: $(cat "$scratch/cube.out")"
[ $(( $(date +%s) - start )) -lt 50 ] || fail "Escape did not end the sketch"
echo "sketch_window.sh: ok"
