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

# --tess 4: per patch 5x5 vertices and 2*4*4 triangles.
stats=$("$tessera" patch "$scratch/two.bpt" -o "$scratch/two.obj" --tess 4 --stats)
grep -qx 'patches=2' <<<"$stats" || { echo "bad stats: $stats"; exit 1; }
grep -qx 'tris=64' <<<"$stats" || { echo "bad stats: $stats"; exit 1; }
grep -qx 'verts=50' <<<"$stats" || { echo "bad stats: $stats"; exit 1; }
grep -q '^area=' <<<"$stats" && grep -q '^seconds=' <<<"$stats"
[ "$(grep -c '^v ' "$scratch/two.obj")" -eq 50 ] || { echo "OBJ vertex count"; exit 1; }
[ "$(grep -c '^vn ' "$scratch/two.obj")" -eq 50 ] || { echo "OBJ normal count"; exit 1; }
[ "$(grep -c '^f ' "$scratch/two.obj")" -eq 64 ] || { echo "OBJ face count"; exit 1; }
# The flat patch is a 3 x 3 square: area 9 plus the bump's, which is larger than its 3 x 3 footprint.
area=$(sed -n 's/^area=//p' <<<"$stats")
awk -v a="$area" 'BEGIN { exit !(a > 18.5 && a < 25) }' || { echo "area $area"; exit 1; }
"$tessera" patch "$scratch/two.bpt" -o "$scratch/flipped.obj" --tess 4 --orient flip
[ "$(grep -c '^f ' "$scratch/flipped.obj")" -eq 64 ] || { echo "flipped OBJ face count"; exit 1; }
# Adaptive: the flat patch needs one step, the bump more.
stats=$("$tessera" patch "$scratch/two.bpt" -o "$scratch/adaptive.ply" --tess 32 --tolerance 0.01 --stats)
tris=$(sed -n 's/^tris=//p' <<<"$stats")
[ "$tris" -gt 2 ] && [ "$tris" -lt 2048 ] || { echo "adaptive tris $tris"; exit 1; }

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
