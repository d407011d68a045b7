"""A Python sketch in a real window: under xvfb-run, run_sketch(window=True) opens an X window; xdotool moves the real
pointer into it, presses a button, types a key, and each grab of the window (ImageMagick's `import`) equals the
headless render of the same state; Escape ends the run with status 0 (sketch_window_check.py does the steps, inside
the X server). Skips without xvfb-run, xauth, xdotool, import, PIL/numpy, or a build without SDL2."""
import os
import pathlib
import shutil
import signal
import subprocess
import sys
import time

import pytest

from tessera import sketch as ts

CHECK = pathlib.Path(__file__).resolve().parent / "sketch_window_check.py"
LIMIT_S = 55  # the whole check, X server included


def test_python_sketch_in_a_real_window(tmp_path):
    for tool in ("xvfb-run", "xauth", "xdotool", "import"):
        if shutil.which(tool) is None:
            pytest.skip(f"no {tool} (a real-window test needs xvfb-run, xauth, xdotool and ImageMagick's import)")
    pytest.importorskip("numpy")
    pytest.importorskip("PIL")
    if not ts.window_supported():
        pytest.skip("tessera was built without SDL2: tessera.sketch.window_supported() is False")

    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    start = time.monotonic()
    # A session (process group) of its own: on a timeout xvfb-run, its Xvfb, the check and the sketch all end.
    child = subprocess.Popen(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", sys.executable, str(CHECK),
                              str(tmp_path)], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, env=env,
                             start_new_session=True)
    try:
        out, _ = child.communicate(timeout=LIMIT_S)
    except subprocess.TimeoutExpired:
        os.killpg(child.pid, signal.SIGKILL)
        out, _ = child.communicate()
        pytest.fail(f"the real-window check ran past {LIMIT_S} s:\n{out}")
    finally:
        if child.poll() is None:
            os.killpg(child.pid, signal.SIGKILL)
            child.wait()
    print(out)
    print(f"real-window check: {time.monotonic() - start:.1f} s")
    assert child.returncode == 0, f"the real-window check failed ({child.returncode}):\n{out}"
    assert "sketch_window_check: ok" in out, out
