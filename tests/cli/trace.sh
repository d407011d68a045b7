#!/usr/bin/env bash
# tessera trace and tessera bench raycast: images, the bench output and --stats keys, the --hits-out format checked
# against the analytic sphere the mesh approximates, and clean failures.
set -euo pipefail
tessera="$1"
scratch="$2"
data="$(cd "$(dirname "$0")/../data" && pwd)"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"

# A unit sphere as a subdivided octahedron (8 * 4^5 triangles, vertices on the sphere): the flat facets stray from
# the sphere by under 1e-3.
/usr/bin/python3 - <<'EOF'
import math
verts = [(1,0,0),(-1,0,0),(0,1,0),(0,-1,0),(0,0,1),(0,0,-1)]
faces = [(0,2,4),(2,1,4),(1,3,4),(3,0,4),(2,0,5),(1,2,5),(3,1,5),(0,3,5)]
for _ in range(5):
    cache, out = {}, []
    def mid(a, b):
        key = (min(a, b), max(a, b))
        if key not in cache:
            p = [(verts[a][k] + verts[b][k]) / 2 for k in range(3)]
            n = math.sqrt(sum(c * c for c in p))
            verts.append(tuple(c / n for c in p))
            cache[key] = len(verts) - 1
        return cache[key]
    for a, b, c in faces:
        ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    faces = out
with open("sphere.obj", "w") as f:
    for v in verts: f.write("v %.9f %.9f %.9f\n" % v)
    for a, b, c in faces: f.write("f %d %d %d\n" % (a + 1, b + 1, c + 1))
open("empty.obj", "w").write("v 0 0 0\n")
EOF

cam=(--eye 0,0,5 --center 0,0,0 --fovy 30 --size 64x48)

# trace: every shading, deterministic for any thread count.
"$tessera" trace sphere.obj -o t1.png "${cam[@]}" --threads 1
"$tessera" trace sphere.obj -o t2.png "${cam[@]}" --threads 2
cmp t1.png t2.png
"$tessera" trace sphere.obj -o n.ppm --shade normal "${cam[@]}" && test -s n.ppm
"$tessera" trace sphere.obj -o c.png --shade cost "${cam[@]}" --stats > trace_stats.txt
keys="triangles pixels width height samples seconds read_s compute_s write_s total_s"
[ "$(sed 's/=.*//' trace_stats.txt | tr '\n' ' ')" = "$keys " ] || { echo "trace: expected $keys"; cat trace_stats.txt; exit 1; }
grep -q '^triangles=8192$' trace_stats.txt

# bench raycast: the one-line summary, the --stats keys, and the hits file.
"$tessera" bench raycast sphere.obj "${cam[@]}" --random-rays 20000 > bench.txt
grep -Eq '^build_s=[0-9.e+-]+ primary_rays_per_s=[0-9.e+-]+ random_rays_per_s=[0-9.e+-]+$' bench.txt \
  || { echo "bad bench line:"; cat bench.txt; exit 1; }
"$tessera" bench raycast sphere.obj "${cam[@]}" --random-rays 1000 --stats --hits-out hits.txt > stats.txt
for key in build_s primary_rays_per_s random_rays_per_s triangles bvh_nodes bvh_depth primary_hit_fraction \
           random_hit_fraction width height threads compute_s read_s write_s total_s; do
  grep -Eq "^$key=[0-9.e+-]+$" stats.txt || { echo "bench: missing $key"; cat stats.txt; exit 1; }
done

# The hits file: one line per primary ray, row-major from the top row, checked against the analytic unit sphere
# (the notes' eye rays: u = (2(i + 1/2)/W - 1) aspect, v = 1 - 2(j + 1/2)/H, direction -d w + u u + v v).
/usr/bin/python3 - <<'EOF'
import math
W, H = 64, 48
d = 1 / math.tan(math.radians(30) / 2)
lines = open("hits.txt").read().split("\n")
assert lines[-1] == "", "no final newline"
lines = lines[:-1]
assert len(lines) == W * H, len(lines)
hits = 0
for k, line in enumerate(lines):
    idx, t, prim = line.split()
    assert int(idx) == k, line
    j, i = divmod(k, W)
    u = (2 * (i + 0.5) / W - 1) * W / H
    v = 1 - 2 * (j + 0.5) / H
    n = math.sqrt(u * u + v * v + d * d)
    dz = -d / n
    # |(0, 0, 5) + t dir|^2 = 1: t^2 + 2 b t + 24 = 0 with b = 5 dz.
    b = 5 * dz
    disc = b * b - 24
    if prim == "-1":
        assert t == "-1", line
        # A miss only where the sphere is missed or grazed (the mesh lies just inside the sphere).
        assert disc < 0.05, line
        continue
    hits += 1
    assert 0 <= int(prim) < 8192, line
    assert disc >= 0, "a hit where the sphere is missed: " + line
    t_sphere = -b - math.sqrt(disc)
    # The facets sag under 1e-3 below the sphere; near the silhouette t is more sensitive.
    assert abs(float(t) - t_sphere) < 2e-3 / max(math.sqrt(disc) / 2.5, 0.05), (line, t_sphere)
assert hits > W * H / 10, hits
EOF

# --ortho: every eye ray runs along -z from (x, y, 5) with x = u h/2, y = v h/2 (h = --ortho-size 3), and meets the
# sphere at t = 5 - sqrt(1 - x^2 - y^2) where x^2 + y^2 < 1; the disk covers pi (1/1.5)^2 / 4 of the square picture.
"$tessera" bench raycast sphere.obj --eye 0,0,5 --center 0,0,0 --ortho --ortho-size 3 --size 60x60 --random-rays 0 \
  --hits-out ortho_hits.txt > /dev/null
"$tessera" trace sphere.obj -o ortho.png --eye 0,0,5 --center 0,0,0 --ortho --ortho-size 3 --size 60x60 \
  --background black
/usr/bin/python3 - <<'EOF'
import math
import numpy as np
from PIL import Image
W = H = 60
hits = 0
for k, line in enumerate(open('ortho_hits.txt').read().split('\n')[:-1]):
    idx, t, prim = line.split()
    j, i = divmod(k, W)
    x, y = (2 * (i + 0.5) / W - 1) * 1.5, (1 - 2 * (j + 0.5) / H) * 1.5
    r2 = x * x + y * y
    if prim == '-1':
        assert r2 > 0.995, line
        continue
    hits += 1
    assert r2 < 1, line
    assert abs(float(t) - (5 - math.sqrt(1 - r2))) < 2e-3 / max(math.sqrt(1 - r2), 0.05), line
assert abs(hits - math.pi / 4 / 1.5**2 * W * H) < 2 * math.pi * W / 3, hits
img = np.asarray(Image.open('ortho.png').convert('L'))
assert (img > 0).sum() == hits, ((img > 0).sum(), hits)
EOF

# --samples: a square x < 0 seen orthographically on 11 pixels across 2 units (--shade normal: blue 1 on a black
# background): the edge x = 0 runs through the centers of column 5, covered by 1/2 within 1/N with N stratified
# samples. --samples 1 is the picture without the option, byte for byte.
cp "$data/half_plane.obj" half.obj
aa=(--eye 0,0,5 --center 0,0,0 --ortho --ortho-size 2 --size 11x11 --shade normal --background black)
"$tessera" trace half.obj -o aa_default.png "${aa[@]}"
"$tessera" trace half.obj -o aa_1.png "${aa[@]}" --samples 1
cmp -s aa_default.png aa_1.png || { echo "--samples 1 differs from the default"; exit 1; }
"$tessera" trace sphere.obj -o s_default.png "${cam[@]}"
"$tessera" trace sphere.obj -o s_1.png "${cam[@]}" --samples 1
cmp -s s_default.png s_1.png || { echo "--samples 1 differs from the default (sphere)"; exit 1; }
for n in 4 9 16 64; do "$tessera" trace half.obj -o "aa_$n.png" "${aa[@]}" --samples "$n"; done
"$tessera" trace sphere.obj -o s_16.png "${cam[@]}" --samples 16 --stats > s_16.txt
grep -q '^samples=16$' s_16.txt || { echo "expected samples=16"; cat s_16.txt; exit 1; }
# --srgb: the sRGB curve of the linear picture's values (where the linear picture's 8-bit rounding matters little).
"$tessera" trace sphere.obj -o s_srgb.png "${cam[@]}" --srgb
/usr/bin/python3 - <<'EOF'
import numpy as np
from PIL import Image
for n in (4, 9, 16, 64):
    a = np.asarray(Image.open(f'aa_{n}.png').convert('RGB')).astype(float)[:, :, 2]
    assert (a[:, :5] == 255).all() and (a[:, 6:] == 0).all(), n
    assert (np.abs(a[:, 5] / 255 - 0.5) <= 1 / n + 0.5 / 255).all(), (n, a[:, 5])
one, many = (np.asarray(Image.open(f).convert('L')).astype(int) for f in ('s_1.png', 's_16.png'))
assert len(np.unique(many)) > len(np.unique(one)), 'no intermediate values'
lin = np.asarray(Image.open('s_1.png').convert('RGB')) / 255.0
srgb = np.asarray(Image.open('s_srgb.png').convert('RGB')).astype(float)
want = np.where(lin <= 0.0031308, 12.92 * lin, 1.055 * lin ** (1 / 2.4) - 0.055) * 255
bright = lin > 0.2
assert bright.sum() > 1000 and np.abs(srgb - want)[bright].max() <= 1.5, np.abs(srgb - want)[bright].max()
EOF

# Errors: exit 1 (2 for usage), a clear message, no output file.
expect_error() {
  local code="$1" pattern="$2" out="$3"
  shift 3
  set +e
  "$tessera" "$@" 2> err.txt > /dev/null
  local rc=$?
  set -e
  [ "$rc" -eq "$code" ] || { echo "expected exit $code, got $rc for: $*"; cat err.txt; exit 1; }
  grep -qi -- "$pattern" err.txt || { echo "message lacks '$pattern':"; cat err.txt; exit 1; }
  [ ! -e "$out" ] || { echo "$out was written"; exit 1; }
}
expect_error 1 "missing.obj" bad.png trace missing.obj -o bad.png
expect_error 1 "no faces" bad.png trace empty.obj -o bad.png
expect_error 2 "size" bad.png trace sphere.obj -o bad.png --size 0x10
expect_error 2 "size" bad.png trace sphere.obj -o bad.png --size 800
expect_error 2 "background" bad.png trace sphere.obj -o bad.png --background nocolor
expect_error 2 "samples" bad.png trace sphere.obj -o bad.png --samples 0
# Options that would change nothing are refused, not ignored: a ray caster has no clipping planes.
expect_error 2 "near" bad.png trace sphere.obj -o bad.png --near 1
expect_error 2 "far" bad_hits.txt bench raycast sphere.obj --far 3 --hits-out bad_hits.txt
expect_error 1 "surface color" bad.png trace sphere.obj -o bad.png --shade normal --color red
expect_error 1 "cost" bad.png trace sphere.obj -o bad.png --shade cost --background white
expect_error 2 "center" bad.png trace sphere.obj -o bad.png --center 0,0
expect_error 2 "eye" bad.png trace sphere.obj -o bad.png --azimuth 30 --eye 0,0,5
expect_error 2 "ortho" bad_hits.txt bench raycast sphere.obj --ortho-size 2 --hits-out bad_hits.txt
expect_error 2 "shade" bad.png trace sphere.obj -o bad.png --shade glow
expect_error 1 "random-rays" bad_hits.txt bench raycast sphere.obj --random-rays -5 --hits-out bad_hits.txt
expect_error 1 "expected N in \[0, 134217728\]" bad_hits.txt bench raycast sphere.obj --random-rays 100000000000 \
  --hits-out bad_hits.txt
expect_error 1 "no faces" bad_hits.txt bench raycast empty.obj --hits-out bad_hits.txt
expect_error 2 "needs a subcommand" none bench
echo "trace CLI ok"
