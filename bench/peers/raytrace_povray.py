#!/usr/bin/python3
"""The Whitted scene: `tessera render whitted` against POV-Ray 3.7 (Debian `povray`) on bench/peers/whitted.pov, at the
same resolution, recursion depth (6) and samples per pixel (POV-Ray: +AM1 +A0.0 +R2 supersamples every pixel on a
2 x 2 grid = 4 samples; Tessera: --spp 4 stratified), same thread count, best of N runs each, in one run.

usage: raytrace_povray.py TESSERA_BINARY [--size WxH] [--threads N] [--runs N]
prints wall and CPU seconds per renderer, `ratio=` (POV-Ray wall seconds / Tessera wall seconds; > 1 means Tessera is
faster) and `cpu_ratio=` (the same for CPU seconds, user + system)."""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

here = os.path.dirname(os.path.abspath(__file__))


def best_time(cmd, runs):
    """Best wall time and best CPU time (user + system of the child) over `runs` runs."""
    best_wall = best_cpu = float("inf")
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        best_wall, best_cpu = min(best_wall, wall), min(best_cpu, cpu)
    return best_wall, best_cpu


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
    print(f"tessera_s={t_tess[0]:.4f}")
    print(f"povray_s={t_pov[0]:.4f}")
    print(f"ratio={t_pov[0] / t_tess[0]:.2f}")
    # CPU seconds are the fairer figure on a loaded machine: POV-Ray's wall time there is often twice its CPU time.
    print(f"tessera_cpu_s={t_tess[1]:.4f}")
    print(f"povray_cpu_s={t_pov[1]:.4f}")
    print(f"cpu_ratio={t_pov[1] / t_tess[1]:.2f}")
    print(f"# size={a.size} spp=4 depth=6 threads={a.threads} best of {a.runs}", file=sys.stderr)


if __name__ == "__main__":
    main()
