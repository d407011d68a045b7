#!/usr/bin/env python3
"""Speed of the Python package (issue 28's benchmarks): a benchmark, not a test (nothing asserts a time).

    .venv/bin/python bench/python/bench_python.py [--quick] [--json FILE] [--cli PATH] [--data DIR]

Prints one table of:

1. Per-call overhead: the median microseconds per call (timeit, calls batched to ~0.2 s, several repeats) of small
   functions (tessera.thread_count(), convert_colors on a (1, 3) array, surface_area of a one-triangle Mesh) next to
   a plain Python function call and a small numpy call for reference. Goal: under 5 us.
2. Color conversion of 1,000,000 random RGB rows (float64) to HSV and HLS: tessera.convert_colors against a Python
   loop over colorsys. The loop is timed on the first 100,000 rows and scaled by 10; it runs over a prepared list of
   tuples (the tolist() conversion is not counted, which favours colorsys: the speed-up is a lower bound; the
   end-to-end loop, tolist() and np.array() of the results included, is given in the detail). Goal: >= 50x. The
   results are compared on those 100,000 rows (max abs diff; hue compared on the circle, 0 == 1 turn).
3. Marching cubes from a numpy array against the C++ call on the same field in the same run: tessera.marching_cubes
   (array, iso) end to end (array conversion, extraction, the Mesh) against `tessera volume isosurface FILE.nrrd
   --stats`'s compute_s (the extraction alone, in a fresh process), the field written with tessera.write_volume.
   Fields: a dense gyroid and value noise (procedural_volume), a sparse one (a sphere of radius 20 voxels in a 256^3
   grid), and real scans from the shared data (foot CT 256^3 as float32 and as its raw uint8 array, headsq 64x64x93)
   at Otsu's threshold (the CLI's default iso, read from `tessera volume info --stats`). copy-in: one astype(float32)
   copy of the input as given (what bringing it into the core's float32 layout costs; the binding makes such a copy).
   ratio = Python wall / C++ compute_s (1.0 = the same speed). The CLI and Python runs alternate, round by round, so
   that load from other work hits both alike. The triangle and vertex counts are checked equal.

Medians throughout. Both sides use tessera.thread_count() threads (the CLI gets the same --threads). --quick: fewer
repeats and rounds (well under a minute); the full run takes about a minute on 2 cores. The shared data is
$TESSERA_SHARED_DATA or ../shared/data next to the repository; a missing file skips its rows, saying so.
"""
import argparse
import colorsys
import datetime
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import tempfile
import time
import timeit

import numpy as np

import tessera

ROOT = pathlib.Path(__file__).resolve().parents[2]
GOAL_CALL_US = 5.0
GOAL_COLOR_SPEEDUP = 50.0


def median(values):
    return statistics.median(values)


# ---------------------------------------------------------------------------------------------------------------------
# 1. Per-call overhead


def noop():
    return 0


def per_call_us(stmt, namespace, target_s, repeats):
    """Median and min microseconds per call of stmt: calls batched to about target_s seconds, `repeats` batches."""
    timer = timeit.Timer(stmt, globals=namespace)
    number = 1
    while True:
        t = timer.timeit(number)
        if t >= target_s / 10 or number >= 10**8:
            break
        number *= 10
    number = max(1, int(number * target_s / max(t, 1e-9)))
    runs = [r / number * 1e6 for r in timer.repeat(repeat=repeats, number=number)]
    return {"median_us": median(runs), "min_us": min(runs), "calls": number, "repeats": repeats}


def bench_overhead(quick):
    a13 = np.array([[0.2, 0.4, 0.6]])
    triangle = tessera.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    namespace = {"tessera": tessera, "np": np, "noop": noop, "a13": a13, "triangle": triangle}
    cases = [
        ("reference", "noop()", "a Python function: def noop(): return 0"),
        ("reference", "np.add(a13, a13)", "a small numpy call, (1, 3) float64"),
        ("tessera", "tessera.thread_count()", "no arguments"),
        ("tessera", "tessera.convert_colors(a13, 'rgb', 'hsv')", "(1, 3) float64 in and out"),
        ("tessera", "tessera.surface_area(triangle)", "a one-triangle tessera.Mesh"),
    ]
    rows = []
    for kind, stmt, what in cases:
        r = per_call_us(stmt, namespace, 0.05 if quick else 0.2, 3 if quick else 7)
        r.update(kind=kind, call=stmt, what=what)
        if kind == "tessera":
            r["goal_met"] = r["median_us"] < GOAL_CALL_US
        rows.append(r)
    return rows


# ---------------------------------------------------------------------------------------------------------------------
# 2. Color conversion


def hue_aware_diff(a, b, hue_column):
    d = np.abs(a - b)
    d[:, hue_column] = np.minimum(d[:, hue_column], 1.0 - d[:, hue_column])
    return float(d.max())


def bench_colors(quick):
    n, n_loop = 1_000_000, 100_000
    rgb = np.random.default_rng(28).random((n, 3))
    rows_list = [tuple(r) for r in rgb[:n_loop].tolist()]
    reps_t, reps_loop = (3, 2) if quick else (7, 5)
    out = []
    for target in ("hsv", "hls"):
        to = getattr(colorsys, "rgb_to_" + target)
        result = tessera.convert_colors(rgb, "rgb", target)  # warm-up, and the result compared below
        times = []
        for _ in range(reps_t):
            t0 = time.perf_counter()
            tessera.convert_colors(rgb, "rgb", target)
            times.append(time.perf_counter() - t0)
        loop, loop_e2e = [], []
        for _ in range(reps_loop):
            t0 = time.perf_counter()
            reference = [to(r, g, b) for r, g, b in rows_list]
            loop.append(time.perf_counter() - t0)
            t0 = time.perf_counter()
            np.array([to(r, g, b) for r, g, b in rgb[:n_loop].tolist()])
            loop_e2e.append(time.perf_counter() - t0)
        scale = n / n_loop
        t_tessera, t_loop, t_e2e = median(times), median(loop) * scale, median(loop_e2e) * scale
        diff = hue_aware_diff(result[:n_loop], np.array(reference), 0)
        out.append({"conversion": "rgb->" + target, "rows": n, "tessera_s": t_tessera, "loop_rows": n_loop,
                    "loop_scaled_s": t_loop, "loop_e2e_scaled_s": t_e2e, "speedup": t_loop / t_tessera,
                    "speedup_e2e": t_e2e / t_tessera, "max_abs_diff": diff,
                    "goal_met": t_loop / t_tessera >= GOAL_COLOR_SPEEDUP, "repeats": reps_t, "loop_repeats": reps_loop})
    return out


# ---------------------------------------------------------------------------------------------------------------------
# 3. Marching cubes


def cli_stats(cmd):
    """The key=value lines a --stats run prints, as floats where they are numbers."""
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed ({p.returncode}): {p.stderr.strip()}")
    stats = {}
    for line in p.stdout.split():
        if "=" in line:
            key, value = line.split("=", 1)
            try:
                stats[key] = float(value)
            except ValueError:
                stats[key] = value
    return stats


def read_mhd_raw(path):
    """The voxels of a MetaImage file as the numpy array (Z, Y, X) a user gets with np.fromfile (uint8, int16 only)."""
    header = {}
    for line in path.read_text().splitlines():
        if "=" in line:
            key, value = line.split("=", 1)
            header[key.strip()] = value.strip()
    dtype = {"MET_UCHAR": np.uint8, "MET_SHORT": np.int16}[header["ElementType"]]
    x, y, z = (int(v) for v in header["DimSize"].split())
    voxels = np.fromfile(path.parent / header["ElementDataFile"], dtype=np.dtype(dtype).newbyteorder("<"))
    return voxels.reshape(z, y, x)


def sphere_field(n, radius):
    """radius - distance to the grid's centre (float32, inside >= 0)."""
    d = np.arange(n, dtype=np.float32) - np.float32((n - 1) / 2)
    squared = d[:, None, None] ** 2 + d[None, :, None] ** 2 + d[None, None, :] ** 2
    return np.float32(radius) - np.sqrt(squared)


def fields(data_dir):
    """(name, description, {variant: array}, iso or None for Otsu's threshold) of each field; notes for skipped ones."""
    out, notes = [], []
    for spec, kind in (("gyroid:160", "dense"), ("noise:160", "dense")):
        field = tessera.procedural_volume(spec).data
        out.append((spec, f"{kind}, procedural_volume, 160^3 float32", {"float32": field}, 0.0))
    out.append(("sphere r20 in 256^3", "sparse, radius 20 voxels, 256^3 float32", {"float32": sphere_field(256, 20.0)},
                0.0))
    volumes = data_dir / "volumes"
    for stem, what in (("foot_256x256x256_uint8", "CT foot 256^3 (uint8 file)"),
                       ("headsq_64x64x93_int16le", "CT head 64x64x93 (int16 file)")):
        mhd = volumes / (stem + ".mhd")
        if not mhd.exists():
            notes.append(f"skipped {stem}: {mhd} not found")
            continue
        variants = {"float32": np.ascontiguousarray(tessera.read_volume(str(mhd)).data, dtype=np.float32)}
        if stem.startswith("foot"):
            variants["uint8 (np.fromfile)"] = read_mhd_raw(mhd)
        out.append((stem.split("_")[0], what, variants, None))
    return out, notes


def bench_marching_cubes(quick, cli, data_dir):
    threads = tessera.thread_count()
    rounds = 3 if quick else 7
    rows, all_notes = [], []
    with tempfile.TemporaryDirectory(prefix="tessera-bench-python-") as tmp:
        tmp = pathlib.Path(tmp)
        field_list, notes = fields(data_dir)
        all_notes += notes
        for name, what, variants, iso in field_list:
            base = variants["float32"]
            nrrd, ply = tmp / "field.nrrd", tmp / "mesh.ply"
            tessera.write_volume(str(nrrd), base)
            if iso is None:
                iso = float(cli_stats([cli, "volume", "info", str(nrrd), "--stats", "--quiet"])["threshold"])
            cmd = [cli, "volume", "isosurface", str(nrrd), "--iso", f"{iso:.9g}", "-o", str(ply), "--stats", "--quiet",
                   "--threads", str(threads)]
            iso32 = float(np.float32(f"{iso:.9g}"))  # what both sides extract at
            first = {}
            for label, array in variants.items():  # warm-up (first-call costs), and the mesh compared with the CLI's
                mesh = tessera.marching_cubes(array, iso32)
                first[label] = (mesh.face_count, mesh.vertex_count, float(tessera.surface_area(mesh)))
                del mesh
            cpp, cpp_read, py, copy = [], [], {k: [] for k in variants}, {k: [] for k in variants}
            stats = None
            for _ in range(rounds):
                stats = cli_stats(cmd)
                cpp.append(stats["compute_s"])
                cpp_read.append(stats["read_s"])
                for label, array in variants.items():
                    t0 = time.perf_counter()
                    mesh = tessera.marching_cubes(array, iso32)
                    py[label].append(time.perf_counter() - t0)
                    del mesh
                    t0 = time.perf_counter()
                    copied = array.astype(np.float32)
                    copy[label].append(time.perf_counter() - t0)
                    del copied
            for label, array in variants.items():
                tris, verts, area = first[label]
                same = tris == stats["triangles"] and verts == stats["vertices"]
                row = {"field": name, "what": what, "input": f"{label} {'x'.join(map(str, array.shape))}",
                       "iso": iso32, "triangles": tris, "vertices": verts, "area_python": area,
                       "area_cli": stats["area"], "same_mesh_counts": same, "python_s": median(py[label]),
                       "copy_in_s": median(copy[label]), "cpp_compute_s": median(cpp), "cpp_read_s": median(cpp_read),
                       "python_all_s": py[label], "cpp_compute_all_s": cpp, "rounds": rounds, "threads": threads}
                row["ratio"] = row["python_s"] / row["cpp_compute_s"]
                row["overhead_s"] = row["python_s"] - row["cpp_compute_s"]
                rows.append(row)
                if not same:
                    all_notes.append(f"{name} {label}: Python mesh {tris} triangles / {verts} vertices, CLI "
                                     f"{stats['triangles']:.0f} / {stats['vertices']:.0f}")
    return rows, all_notes


# ---------------------------------------------------------------------------------------------------------------------
# The table


def table(rows):
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    lines = []
    for k, r in enumerate(rows):
        lines.append("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    return "\n".join(lines)


def report(meta, overhead, colors, mc, notes):
    rows = [("benchmark", "case", "result", "detail")]
    for r in overhead:
        goal = "reference" if r["kind"] == "reference" else "goal < 5 us: " + ("met" if r["goal_met"] else "NOT met")
        rows.append(("call overhead", r["call"], f"{r['median_us']:.3f} us/call",
                     f"{goal}; {r['what']}; min {r['min_us']:.3f} us, {r['calls']:,} calls x {r['repeats']}"))
    for r in colors:
        rows.append(("colors 1e6 rows", f"{r['conversion']} tessera.convert_colors", f"{r['tessera_s'] * 1e3:.1f} ms",
                     f"median of {r['repeats']}"))
        rows.append(("", f"{r['conversion']} colorsys loop", f"{r['loop_scaled_s'] * 1e3:.0f} ms",
                     f"100,000 rows x10 (median of {r['loop_repeats']}); with tolist()+np.array(): "
                     f"{r['loop_e2e_scaled_s'] * 1e3:.0f} ms"))
        rows.append(("", f"{r['conversion']} speed-up", f"{r['speedup']:.1f}x",
                     f"{r['speedup_e2e']:.1f}x end to end; goal >= 50x: {'met' if r['goal_met'] else 'NOT met'}; "
                     f"max abs diff {r['max_abs_diff']:.1e}"))
    for r in mc:
        rows.append(("marching cubes", f"{r['field']} {r['input']} iso {r['iso']:.6g}",
                     f"{r['ratio']:.2f}x C++",
                     f"Python {r['python_s'] * 1e3:.1f} ms vs C++ compute_s {r['cpp_compute_s'] * 1e3:.1f} ms "
                     f"({r['overhead_s'] * 1e3:+.1f} ms); copy-in {r['copy_in_s'] * 1e3:.1f} ms; "
                     f"{r['triangles']:,} triangles{'' if r['same_mesh_counts'] else ' (COUNTS DIFFER)'}"))
    if mc:
        worst, best = max(mc, key=lambda r: r["ratio"]), min(mc, key=lambda r: r["ratio"])
        rows.append(("marching cubes", "worst / best (Python / C++)", f"{worst['ratio']:.2f}x / {best['ratio']:.2f}x",
                     f"worst {worst['field']} {worst['input'].split()[0]}, best {best['field']} "
                     f"{best['input'].split()[0]}"))
    head = (f"tessera {meta['tessera']} | Python {meta['python']} | numpy {meta['numpy']} | "
            f"{meta['cpu_count']} cores, tessera.thread_count() = {meta['thread_count']} | load average "
            f"{meta['load_before'][0]:.2f} before, {meta['load_after'][0]:.2f} after | {meta['date']}"
            f"{' | --quick' if meta['quick'] else ''}")
    text = head + "\n" + table(rows)
    if notes:
        text += "\n" + "\n".join("note: " + n for n in notes)
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="fewer repeats and rounds (well under a minute)")
    ap.add_argument("--json", metavar="FILE", help="also write the figures as JSON")
    ap.add_argument("--cli", default=str(ROOT / "build" / "release" / "apps" / "tessera" / "tessera"),
                    help="the tessera CLI of the C++ side (default: build/release/apps/tessera/tessera)")
    ap.add_argument("--data", default=os.environ.get("TESSERA_SHARED_DATA", str(ROOT.parent / "shared" / "data")),
                    help="the shared data folder (default: $TESSERA_SHARED_DATA or ../shared/data)")
    a = ap.parse_args()
    started = time.perf_counter()
    meta = {"date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"), "quick": a.quick,
            "tessera": tessera.__version__, "python": platform.python_version(), "numpy": np.__version__,
            "machine": platform.machine(), "cpu_count": os.cpu_count(), "thread_count": tessera.thread_count(),
            "load_before": os.getloadavg(), "command": " ".join([sys.executable] + sys.argv)}
    notes = []
    overhead = bench_overhead(a.quick)
    colors = bench_colors(a.quick)
    mc = []
    if os.access(a.cli, os.X_OK):
        mc, mc_notes = bench_marching_cubes(a.quick, a.cli, pathlib.Path(a.data))
        notes += mc_notes
    else:
        notes.append(f"marching cubes skipped: no CLI at {a.cli} (build the release preset, or pass --cli)")
    meta["load_after"] = os.getloadavg()
    meta["seconds"] = time.perf_counter() - started
    notes.append(f"ran in {meta['seconds']:.0f} s; medians; timings on a shared machine vary from run to run")
    print(report(meta, overhead, colors, mc, notes))
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"meta": meta, "call_overhead": overhead, "colors": colors, "marching_cubes": mc, "notes": notes},
                      f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
