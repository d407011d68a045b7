# What the CLI tests that open a real window share (sourced, not run: `. "$(dirname "$0")/window_lib.sh"`). The
# test runs itself twice: outside an X server it checks its tools and re-runs itself inside xvfb-run with --inside.
#
#   window_prepare SCRATCH                skips (77) without xvfb-run, xdotool, import or PIL/numpy; empties SCRATCH
#   window_enter_x TESSERA SCRATCH ARG... skips (77) when `TESSERA ARG...` run without a display says tessera was
#                                         built without SDL2; else runs the calling script again under xvfb-run as
#                                         `bash SCRIPT TESSERA SCRATCH --inside`
#   compare_grab GRAB WANT [SCALE OX OY]  true when the window grab GRAB is within 1/255 of the headless render WANT
#                                         on at least 99% of the pixels (PIL and numpy, independent of Tessera); with
#                                         a SCALE the window shows the render scaled by it at offset (OX, OY): the
#                                         grab is sampled at the centers of the render's pixels, and the bars beside
#                                         it must be black
window_python=/usr/bin/python3

window_prepare() {  # SCRATCH
  local tool
  for tool in xvfb-run xdotool import; do
    command -v $tool >/dev/null || { echo "${0##*/}: skipped, no $tool"; exit 77; }
  done
  "$window_python" -c 'import PIL, numpy' 2>/dev/null || { echo "${0##*/}: skipped, no PIL/numpy"; exit 77; }
  rm -rf "$1" && mkdir -p "$1"
}

window_enter_x() {  # TESSERA SCRATCH ARG...
  local tessera=$1 scratch=$2 probe
  shift 2
  # The probe fails (no display) either way: only its message tells a build without SDL2.
  probe=$(env -u DISPLAY -u WAYLAND_DISPLAY "$tessera" "$@" 2>&1 || true)
  if grep -q "built without SDL2" <<<"$probe"; then
    echo "${0##*/}: skipped, tessera was built without SDL2"
    exit 77
  fi
  exec xvfb-run -a -s "-screen 0 1280x1024x24" bash "$0" "$tessera" "$scratch" --inside
}

compare_grab() {  # GRAB WANT [SCALE OX OY]
  "$window_python" - "$1" "$2" "${3:-1}" "${4:-0}" "${5:-0}" <<'PY'
import sys
import numpy as np
from PIL import Image
grab = np.asarray(Image.open(sys.argv[1]).convert("RGB")).astype(int)
want = np.asarray(Image.open(sys.argv[2]).convert("RGB")).astype(int)
scale, ox, oy = float(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
h, w = want.shape[:2]
if scale != 1:
    ys = oy + np.floor((np.arange(h) + 0.5) * scale).astype(int)
    xs = ox + np.floor((np.arange(w) + 0.5) * scale).astype(int)
    bars = np.concatenate([grab[:, :ox].reshape(-1, 3), grab[:, ox + int(w * scale):].reshape(-1, 3)])
    if bars.size and bars.max() > 1:
        sys.exit(f"{sys.argv[1]}: the letterbox bars are not black (max {bars.max()})")
    grab = grab[ys][:, xs]
if grab.shape != want.shape:
    sys.exit(f"{sys.argv[1]}: grab {grab.shape} vs headless {want.shape}")
close = (np.abs(grab - want).max(axis=2) <= 1).mean()
print(f"{sys.argv[1]}: {100 * close:.3f}% of pixels within 1/255")
sys.exit(0 if close >= 0.99 else 1)
PY
}
