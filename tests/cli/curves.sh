#!/usr/bin/env bash
# tessera patch and tessera curve end to end: a .bpt written here becomes an OBJ with the expected counts, a curve
# becomes a PNG and an SVG, and bad input exits 1 with "tessera: error:" (usage errors 2).
set -euo pipefail
tessera=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"

expect_exit() {  # expect_exit CODE PATTERN COMMAND...
  local code=$1 pattern=$2; shift 2
  local status=0
  "$@" 2>"$scratch/stderr" >/dev/null || status=$?
  [ "$status" -eq "$code" ] || { echo "expected exit $code, got $status: $*"; cat "$scratch/stderr"; exit 1; }
  grep -q -- "$pattern" "$scratch/stderr" || { echo "stderr lacks '$pattern': $*"; cat "$scratch/stderr"; exit 1; }
}

# Two patches: a flat square and a bump beside it.
cat >"$scratch/two.bpt" <<'BPT'
2
3 3
0 0 0
0 1 0
0 2 0
0 3 0
1 0 0
1 1 0
1 2 0
1 3 0
2 0 0
2 1 0
2 2 0
2 3 0
3 0 0
3 1 0
3 2 0
3 3 0
3 3
3 0 0
3 1 0
3 2 0
3 3 0
4 0 0
4 1 1
4 2 1
4 3 0
5 0 0
5 1 1
5 2 1
5 3 0
6 0 0
6 1 0
6 2 0
6 3 0
BPT

# --tess 4: per patch 5x5 vertices and 2*4*4 triangles; welded (the default), the 5 vertices of the shared border
# count once: 45. --no-weld keeps 50. tris/verts/seconds are the deprecated aliases of triangles/vertices/total.
stats=$("$tessera" patch "$scratch/two.bpt" -o "$scratch/two.obj" --tess 4 --stats)
for key in patches=2 triangles=64 faces=64 vertices=45 tris=64 verts=45; do
  grep -qx "$key" <<<"$stats" || { echo "bad stats ($key): $stats"; exit 1; }
done
for key in area volume read_s compute_s write_s total_s seconds; do
  grep -q "^$key=" <<<"$stats" || { echo "stats lack $key: $stats"; exit 1; }
done
[ "$(grep -c '^v ' "$scratch/two.obj")" -eq 45 ] || { echo "OBJ vertex count"; exit 1; }
[ "$(grep -c '^f ' "$scratch/two.obj")" -eq 64 ] || { echo "OBJ face count"; exit 1; }
stats=$("$tessera" patch "$scratch/two.bpt" -o "$scratch/unwelded.obj" --tess 4 --no-weld --stats)
grep -qx 'vertices=50' <<<"$stats" || { echo "--no-weld stats: $stats"; exit 1; }
[ "$(grep -c '^vn ' "$scratch/unwelded.obj")" -eq 50 ] || { echo "OBJ normal count"; exit 1; }
# The flat patch is a 3 x 3 square: area 9 plus the bump's, which is larger than its 3 x 3 footprint.
area=$(sed -n 's/^area=//p' <<<"$stats")
awk -v a="$area" 'BEGIN { exit !(a > 18.5 && a < 25) }' || { echo "area $area"; exit 1; }
"$tessera" patch "$scratch/two.bpt" -o "$scratch/flipped.obj" --tess 4 --orient flip
[ "$(grep -c '^f ' "$scratch/flipped.obj")" -eq 64 ] || { echo "flipped OBJ face count"; exit 1; }
# Adaptive: the flat patch needs one step, the bump more.
stats=$("$tessera" patch "$scratch/two.bpt" -o "$scratch/adaptive.ply" --tess 32 --tolerance 0.01 --stats)
tris=$(sed -n 's/^tris=//p' <<<"$stats")
[ "$tris" -gt 2 ] && [ "$tris" -lt 2048 ] || { echo "adaptive tris $tris"; exit 1; }

# Newell's teapot (the README's example). Its 32 patches, read off the control points: 16 patch borders are shared by
# no other patch (the rim's inner edge and the lid's outer edge, 4 each; both ends of the 2-patch handle and spout
# tubes, 2 each), every other border is shared by exactly two patches, and 8 borders collapse to the lid tip and the
# bottom centre. So welded at --tess N: 4 components (body with rim and bottom, lid, handle, spout), 6 boundary loops
# of 16 N edges in all, a manifold, consistently oriented mesh; facing outward, the volume is positive and the normal
# at the topmost point (the lid tip, z = 3.15) points up.
teapot="${TESSERA_SHARED_DATA:-}/bezier/teapot.bpt"
if [ -f "$teapot" ]; then
  "$tessera" patch "$teapot" -o "$scratch/teapot.obj" --tess 8
  info=$("$tessera" mesh info "$scratch/teapot.obj" --stats)
  for key in components=4 boundary_loops=6 boundary_edges=128 nonmanifold_edges=0 nonmanifold_vertices=0 oriented=1; do
    grep -qx "$key" <<<"$info" || { echo "teapot: expected $key: $info"; exit 1; }
  done
  "$tessera" patch "$teapot" -o "$scratch/teapot16.obj" --tess 16
  "$tessera" mesh info "$scratch/teapot16.obj" --stats | grep -qx boundary_edges=256 || { echo "teapot --tess 16"; exit 1; }
  /usr/bin/python3 - "$scratch/teapot.obj" <<'EOF'
import sys
v, vn, faces = [], [], []
for line in open(sys.argv[1]):
    w = line.split()
    if not w: continue
    if w[0] == 'v': v.append(tuple(map(float, w[1:4])))
    elif w[0] == 'vn': vn.append(tuple(map(float, w[1:4])))
    elif w[0] == 'f': faces.append([tuple(int(i) - 1 if i else None for i in c.split('/')) for c in w[1:]])
def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1]*b[2] - a[2]*b[1], a[2]*b[0] - a[0]*b[2], a[0]*b[1] - a[1]*b[0])
# Signed volume (divergence theorem); the openings are small and roughly level, so it stays near the closed value.
vol = sum(sum(x * y for x, y in zip(v[f[0][0]], cross(v[f[i][0]], v[f[i + 1][0]]))) / 6
          for f in faces for i in range(1, len(f) - 1))
assert vol > 0, f"signed volume {vol} is not positive: the teapot is inside out"
top = max(range(len(v)), key=lambda i: v[i][2])
assert abs(v[top][2] - 3.15) < 1e-9, v[top]
ups = [vn[c[2]][2] for f in faces for c in f if c[0] == top]
assert ups and min(ups) > 0.99, f"normals at the lid tip: {ups}"
geo = [cross(sub(v[f[1][0]], v[f[0][0]]), sub(v[f[2][0]], v[f[0][0]]))[2] for f in faces if any(c[0] == top for c in f)]
assert geo and min(geo) > 0, "the triangles around the lid tip face down"
print(f"teapot: volume {vol:.3f}, {len(ups)} corners at the tip")
EOF
  "$tessera" patch "$teapot" -o "$scratch/inside_out.obj" --tess 8 --orient given --stats | grep -q '^volume=-' ||
    { echo "--orient given keeps the data's inward winding"; exit 1; }
else
  echo "skipped the teapot checks: no shared data in TESSERA_SHARED_DATA"
fi

# Curves: a cubic to PNG and SVG, a quintic with forward-difference steps.
"$tessera" curve --points 40,360,80,40,320,40,360,360 --t 0.75 --split -o "$scratch/cubic.png"
[ "$(head -c 8 "$scratch/cubic.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || { echo "not a PNG"; exit 1; }
"$tessera" curve --points 40,360,80,40,320,40,360,360 -o "$scratch/cubic.svg" --size 400x400
grep -q '<svg' "$scratch/cubic.svg" && grep -q '</svg>' "$scratch/cubic.svg"
stats=$("$tessera" curve --points 10,10,50,90,90,10,130,90,170,10,190,50 --steps 50 -o "$scratch/q.svg" --stats)
grep -qx 'degree=5' <<<"$stats" || { echo "bad curve stats: $stats"; exit 1; }
for key in length width height pixels compute_s write_s total_s; do
  grep -q "^$key=" <<<"$stats" || { echo "curve stats lack $key: $stats"; exit 1; }
done
# --srgb: the picture is the linear one (PFM) through the sRGB formula.
"$tessera" curve --points 12,108,24,12,96,12,108,108 --t 0.75 --split -o "$scratch/cubic.pfm" --size 120x120
"$tessera" curve --points 12,108,24,12,96,12,108,108 --t 0.75 --split -o "$scratch/cubic_srgb.png" --size 120x120 \
  --srgb
/usr/bin/python3 "$(dirname "$0")/srgb_check.py" pfm "$scratch/cubic.pfm" "$scratch/cubic_srgb.png" ||
  { echo "curve --srgb"; exit 1; }

# Errors: runtime errors exit 1, usage errors 2.
{ printf '1\n3 3\n'; for i in $(seq 15); do echo "0.000 0.000 0.000"; done; echo "0 0"; } >"$scratch/short.bpt"
expect_exit 1 "short.bpt:18: expected z of control point 16 of patch 1, got end of file" \
  "$tessera" patch "$scratch/short.bpt" -o "$scratch/x.obj"
{ printf '1\n3 2\n'; for i in $(seq 16); do echo "0 0 0"; done; } >"$scratch/degree.bpt"
expect_exit 1 "to be 3 (bicubic)" "$tessera" patch "$scratch/degree.bpt" -o "$scratch/x.obj"
expect_exit 1 "tessera: error:" "$tessera" patch "$scratch/two.bpt" -o "$scratch/x.unknown"
expect_exit 1 "tessera: error:" "$tessera" patch "$scratch/two.bpt" -o /proc/forbidden/x.obj
expect_exit 2 "tessera: error: --points: expected 2 to 1000 x,y pairs, got 3 numbers" \
  "$tessera" curve --points 1,2,3 -o "$scratch/x.svg"
expect_exit 2 "tessera: error: --points" "$tessera" curve --points 1,2,3,nan -o "$scratch/x.svg"
expect_exit 2 "tessera: error: --size" "$tessera" curve --points 1,2,3,4 -o "$scratch/x.svg" --size 0x10
expect_exit 2 "tessera: error: --size" "$tessera" curve --points 1,2,3,4 -o "$scratch/x.png" --size 400
expect_exit 2 "" "$tessera" patch "$scratch/two.bpt" -o "$scratch/x.obj" --tess 0
expect_exit 2 "" "$tessera" patch "$scratch/missing.bpt" -o "$scratch/x.obj"
expect_exit 2 "" "$tessera" patch "$scratch/two.bpt" -o "$scratch/x.obj" --orient sideways
expect_exit 2 "" "$tessera" curve --points 1,2,3,4 -o "$scratch/x.svg" --t 2
[ ! -e "$scratch/x.obj" ] && [ ! -e "$scratch/x.svg" ] || { echo "a failed command left a file"; exit 1; }
echo "cli curves: ok"
