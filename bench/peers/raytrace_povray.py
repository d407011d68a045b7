#!/usr/bin/python3
"""The Whitted scene: `tessera render whitted` against POV-Ray 3.7 (Debian `povray`) on bench/peers/whitted.pov, at the
same resolution, recursion depth (6) and samples per pixel (POV-Ray: +AM1 +A0.0 +R2 supersamples every pixel on a
2 x 2 grid = 4 samples; Tessera: --spp 4 stratified), same thread count, best of N runs each, in one run.

usage: raytrace_povray.py TESSERA_BINARY [--size WxH] [--threads N] [--runs N]
prints wall and CPU seconds per renderer end to end (start-up, parsing, rendering, PNG output), `ratio=` (POV-Ray wall
seconds / Tessera wall seconds; > 1 means Tessera is faster) and `cpu_ratio=` (the same for CPU seconds, user +
system). Then, from one more run of each with statistics: the rendering alone (`tessera_render_s=`, the renderer's own
wall clock, against `povray_trace_cpu_s=`, POV-Ray's "Trace Time" CPU seconds; `render_ratio=`), the eye rays and
shadow rays each traced, and a cross-check with exactly Tessera's number of eye rays: POV-Ray's method 1 first traces
one ray per pixel (plus a row) and then the 2 x 2 supersamples, about 26% more eye rays than 4 per pixel, so
`povray_2x_cpu_s=` renders at twice the size without antialiasing (4 eye rays per output pixel, a 4x larger PNG)
and `cpu_ratio_2x=` compares Tessera with that."""
import argparse
import os
import re
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


def field(pattern, text):
    """The first group of the first (multi-line) match of pattern in text."""
    return re.search(pattern, text, re.M).group(1)


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
        pov_2x_cmd = [c for c in pov_cmd if c not in ("+AM1", "+A0.0", "+R2")]
        pov_2x_cmd[pov_2x_cmd.index("+W" + w)] = f"+W{2 * int(w)}"
        pov_2x_cmd[pov_2x_cmd.index("+H" + h)] = f"+H{2 * int(h)}"
        t_pov_2x = best_time(pov_2x_cmd + ["-A"], a.runs)
        tess_stats = [subprocess.run(tess_cmd + ["--stats"], check=True, capture_output=True, text=True).stdout
                      for _ in range(a.runs)]
        pov_stats = subprocess.run([c if c != "-GA" else "+GA" for c in pov_cmd], check=True, capture_output=True,
                                   text=True).stderr
    print(f"tessera_s={t_tess[0]:.4f}")
    print(f"povray_s={t_pov[0]:.4f}")
    print(f"ratio={t_pov[0] / t_tess[0]:.2f}")
    # CPU seconds are the fairer figure on a loaded machine: POV-Ray's wall time there is often twice its CPU time.
    print(f"tessera_cpu_s={t_tess[1]:.4f}")
    print(f"povray_cpu_s={t_pov[1]:.4f}")
    print(f"cpu_ratio={t_pov[1] / t_tess[1]:.2f}")
    # The rendering alone: Tessera's own clock (wall, best of the runs; on a loaded machine a bound above its CPU time)
    # against POV-Ray's trace CPU seconds.
    tess_render = min(float(field(r"^seconds=([0-9.e+-]+)", stats)) for stats in tess_stats)
    tess_stats = tess_stats[0]
    pov_trace = float(field(r"Trace Time:.*\n.*with ([0-9.]+) CPU-seconds", pov_stats))
    print(f"tessera_render_s={tess_render:.4f}")
    print(f"povray_trace_cpu_s={pov_trace:.4f}")
    print(f"render_ratio={pov_trace / tess_render:.2f}")
    pixels, samples = field(r"Pixels:\s+([0-9]+)", pov_stats), field(r"Samples:\s+([0-9]+)", pov_stats)
    counts = {
        "tessera_eye_rays": field(r"^eye_rays=([0-9]+)", tess_stats),
        "tessera_rays": field(r"^rays=([0-9]+)", tess_stats) + "  # eye, reflected, refracted, shadow",
        "povray_eye_rays": f"{int(pixels) + int(samples)}  # {pixels} first rays + {samples} supersamples",
        "povray_rays": field(r"Rays:\s+([0-9]+)", pov_stats) + "  # eye, reflected, refracted",
        "povray_shadow_rays": field(r"Shadow Ray Tests:\s+([0-9]+)", pov_stats),
    }
    for key, value in counts.items():
        print(f"{key}={value}")
    print(f"povray_2x_cpu_s={t_pov_2x[1]:.4f}")
    print(f"cpu_ratio_2x={t_pov_2x[1] / t_tess[1]:.2f}")
    print(f"# size={a.size} spp=4 depth=6 threads={a.threads} best of {a.runs}", file=sys.stderr)


if __name__ == "__main__":
    main()
