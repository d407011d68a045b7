"""A Python sketch in a real window, checked from outside (run inside an X server by test_sketch_window.py, as
`xvfb-run -a -s "-screen 0 1280x1024x24" python sketch_window_check.py SCRATCH`).

The notes' pink_square as a Python sketch (a pink square that follows the mouse, darker while a button is held, 's'
toggles a black outline; examples/python/sketches/pink_square.py) opens a 400x400 window with
run_sketch(module, window=True); xdotool moves the real pointer into it, presses and releases a button, types a key,
and after each step ImageMagick's `import` grabs the window. Each grab must match the
headless render of the same state (run_sketch with an input script setting the same mouse position, button and key
at frame 1, one frame) within 1/255 on at least 99% of the pixels, as tests/cli/window_lib.sh's compare_grab. Escape
then ends the run: the sketch process must exit with status 0. Exit status 0 when all holds, else 1 with the reason.
"""
import os
import pathlib
import subprocess
import sys
import time

import numpy as np
from PIL import Image

TITLE = "python sketch window test"
# The notes' pink_square as Python (examples/python/sketches/pink_square.py), loaded as a module and run by
# run_sketch(module): in the window, or headless for one frame of a scripted state.
EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "sketches" / "pink_square.py"
SKETCH = f'''import importlib.util
import sys

from tessera.sketch import run_sketch

spec = importlib.util.spec_from_file_location("pink_square", {str(EXAMPLE)!r})
module = importlib.util.module_from_spec(spec)
spec.loader.exec_module(module)
if sys.argv[1] == "window":
    print("result", run_sketch(module, window=True, seconds=60, title={TITLE!r}), flush=True)
else:  # headless INPUT OUTPUT: one frame of the scripted state
    run_sketch(module, frames=1, input=sys.argv[2], output=sys.argv[3])
'''
GRAB_TRIES = 6  # a grab that does not match yet is taken again (the window may not have drawn the new state)


class Failure(Exception):
    pass


def xdotool(*args, timeout=10):
    r = subprocess.run(["xdotool", *map(str, args)], capture_output=True, text=True, timeout=timeout)
    if r.returncode != 0:
        raise Failure(f"xdotool {' '.join(map(str, args))} failed ({r.returncode}): {r.stderr.strip()}")
    return r.stdout


def closeness(grab_path, want_path, before_path):
    """The fraction of pixels within 1/255 in every channel (compare_grab of window_lib.sh, at scale 1), and that
    fraction among the pixels where the render differs from the one before the step (the outline of a key press is
    under 1% of the picture: the step must show there too)."""
    grab, want, before = (np.asarray(Image.open(p).convert("RGB")).astype(int)
                          for p in (grab_path, want_path, before_path))
    if grab.shape != want.shape:
        raise Failure(f"{grab_path}: grab {grab.shape} vs headless {want.shape}")
    close = np.abs(grab - want).max(axis=2) <= 1
    changed = np.abs(want - before).max(axis=2) > 1
    if not changed.any():
        raise Failure(f"{want_path}: the headless render equals the one before the step")
    return close.mean(), close[changed].mean()


def main():
    scratch = pathlib.Path(sys.argv[1])
    scratch.mkdir(parents=True, exist_ok=True)
    script = scratch / "window_sketch.py"
    script.write_text(SKETCH)
    env = {k: v for k, v in os.environ.items() if k != "WAYLAND_DISPLAY"}  # the X server of xvfb-run, not Wayland

    def headless(name, events):
        (scratch / f"{name}.txt").write_text(events)
        subprocess.run([sys.executable, script, "headless", scratch / f"{name}.txt", scratch / f"{name}-headless.png"],
                       check=True, env=env, cwd=scratch, timeout=30)

    # The headless renders first (they need no window): the states the window will be driven through, and each
    # step's state before it (the start: no events, the pointer at (0, 0)).
    states = {"start": "",
              "move": "1 mouse_move 100 80\n",
              "drag": "1 mouse_move 100 80\n1 mouse_press left\n1 mouse_move 150 120\n",
              "released": "1 mouse_move 150 120\n",
              "key": "1 mouse_move 150 120\n1 key_press s\n"}
    for name, events in states.items():
        headless(name, events)

    log = open(scratch / "window.out", "w")
    sketch = subprocess.Popen([sys.executable, script, "window"], stdout=log, stderr=subprocess.STDOUT, env=env,
                              cwd=scratch)
    try:
        def output():
            log.flush()
            return (scratch / "window.out").read_text()

        # Its window, by the process id SDL sets (_NET_WM_PID), and then its title. (Not `xdotool search --name`:
        # in a Python process, whose locale is UTF-8, SDL writes WM_NAME with the type "UTF-8", which xdotool's
        # name search does not decode; _NET_WM_NAME, which getwindowname reads, is right.)
        wid = ""
        deadline = time.monotonic() + 20
        while not wid:
            if sketch.poll() is not None:
                raise Failure(f"the sketch ended ({sketch.returncode}) before its window appeared: {output()}")
            if time.monotonic() > deadline:
                raise Failure(f"no window appeared in 20 s: {output()}")
            try:
                r = subprocess.run(["xdotool", "search", "--sync", "--pid", str(sketch.pid)], capture_output=True,
                                   text=True, timeout=2)
            except subprocess.TimeoutExpired:
                continue
            for window in r.stdout.split():
                name = subprocess.run(["xdotool", "getwindowname", window], capture_output=True, text=True,
                                      timeout=10).stdout.strip()
                if name == TITLE:
                    wid = window
                    break
            else:
                time.sleep(0.2)
        geometry = xdotool("getwindowgeometry", wid)
        if "Geometry: 400x400" not in geometry:
            raise Failure(f"the window is not 400x400: {geometry}")

        def check(name, before):
            """Grabs the window until it shows the headless render of `name` (a few tries, 0.5 s apart): within
            1/255 on 99% of the pixels, and on 99% of those the step changed from the state `before`."""
            grab = scratch / f"{name}-window.png"
            for attempt in range(GRAB_TRIES):
                time.sleep(0.5)
                subprocess.run(["import", "-window", wid, grab], check=True, capture_output=True, timeout=15)
                close, changed = closeness(grab, scratch / f"{name}-headless.png", scratch / f"{before}-headless.png")
                print(f"{name}: {100 * close:.3f}% of pixels within 1/255, {100 * changed:.3f}% of those the step "
                      f"changed (grab {attempt + 1})", flush=True)
                if close >= 0.99 and changed >= 0.99:
                    return
                if sketch.poll() is not None:
                    break
            raise Failure(f"{name}: the window differs from the headless render ({100 * close:.3f}% within 1/255, "
                          f"{100 * changed:.3f}% of the pixels the step changed)")

        # The pointer moves into the window: the square follows it.
        xdotool("mousemove", "--window", wid, 100, 80)
        check("move", "start")
        # A button held while the pointer moves: the square darkens; then released.
        xdotool("mousedown", 1)
        xdotool("mousemove", "--window", wid, 150, 120)
        check("drag", "move")
        xdotool("mouseup", 1)
        # A key typed into the focused window: 's' toggles the outline.
        xdotool("windowfocus", "--sync", wid)
        xdotool("key", "s")
        check("key", "released")

        # Escape ends the run, as in Processing: status 0, well before the 60 seconds.
        xdotool("windowfocus", "--sync", wid)
        xdotool("key", "Escape")
        try:
            status = sketch.wait(timeout=10)
        except subprocess.TimeoutExpired:
            raise Failure(f"the sketch did not end within 10 s of Escape: {output()}")
        if status != 0:
            raise Failure(f"the sketch exited {status} after Escape: {output()}")
        print("sketch output:", output().strip(), flush=True)
        print("sketch_window_check: ok", flush=True)
    finally:
        if sketch.poll() is None:
            sketch.kill()
            sketch.wait()
        log.close()


if __name__ == "__main__":
    try:
        main()
    except (Failure, subprocess.SubprocessError, OSError) as e:
        print(f"sketch_window_check: {e}", flush=True)
        sys.exit(1)
