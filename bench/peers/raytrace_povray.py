#!/usr/bin/python3
"""The Whitted scene: `tessera render whitted` against POV-Ray 3.7 (Debian `povray`) on bench/peers/whitted.pov, at the
same resolution, recursion depth (6) and samples per pixel (POV-Ray: +AM1 +A0.0 +R2 supersamples every pixel on a
2 x 2 grid = 4 samples; Tessera: --spp 4 stratified), same thread count, best of N runs each, in one run.

usage: raytrace_povray.py TESSERA_BINARY [--size WxH] [--threads N] [--runs N]
prints one line per renderer and `ratio=` (POV-Ray seconds / Tessera seconds; > 1 means Tessera is faster)."""
import argparse
import os
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))


def best_time(cmd, runs):
    best = float("inf")
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        best = min(best, time.perf_counter() - start)
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("tessera")
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--threads", type=int, default=os.cpu_count())
    ap.add_argument("--runs", type=int, default=3)
    a = ap.parse_args()
    w, h = a.size.split("x")
    with tempfile.TemporaryDirectory() as tmp:
        tess_cmd = [a.tessera, "render", "whitted", "-o", os.path.join(tmp, "tessera.png"), "--size", a.size,
                    "--spp", "4", "--depth", "6", "--threads", str(a.threads), "--quiet"]
        pov_cmd = ["povray", "+I" + os.path.join(here, "whitted.pov"), "+O" + os.path.join(tmp, "povray.png"),
                   "+W" + w, "+H" + h, "-D", "+FN", "+Q9", "+AM1", "+A0.0", "+R2", "+WT" + str(a.threads), "-GA"]
        t_tess = best_time(tess_cmd, a.runs)
        t_pov = best_time(pov_cmd, a.runs)
    print(f"tessera_s={t_tess:.4f}")
    print(f"povray_s={t_pov:.4f}")
    print(f"ratio={t_pov / t_tess:.2f}")
    print(f"# size={a.size} spp=4 depth=6 threads={a.threads} best of {a.runs}", file=sys.stderr)


if __name__ == "__main__":
    main()
