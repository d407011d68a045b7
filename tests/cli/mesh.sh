#!/usr/bin/env bash
# tessera mesh: info --stats on a hand-written cube, conversions through every format and back, normals, smoothing,
# triangulation, and the error paths (missing file, malformed line, usage errors).
# $1 = the tessera binary, $2 = a scratch folder.
set -euo pipefail
tessera=$1
dir=$2
cli_dir="$(cd "$(dirname "$0")" && pwd)"  # obj_corners.py
rm -rf "$dir"
mkdir -p "$dir"
cd "$dir"

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# The unit cube [0,1]^3, quads counterclockwise seen from outside.
cat >cube.obj <<'OBJ'
# a unit cube
mtllib cube.mtl
o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
g faces
usemtl grey
s off
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 3 7 6
OBJ

expected="vertices=8
faces=6
edges=12
boundary_edges=0
boundary_loops=0
components=1
euler=2
genus=0
nonmanifold_edges=0
nonmanifold_vertices=0
unreferenced_vertices=0
oriented=1
bbox_min=0,0,0
bbox_max=1,1,1
area=6
volume=1"
got=$("$tessera" mesh info cube.obj --stats)
[ "$(grep -v -E '^(read_s|compute_s|total_s)=' <<<"$got")" = "$expected" ] || fail "info --stats of the cube: got
$got"
for key in read_s compute_s total_s; do grep -q "^$key=" <<<"$got" || fail "info --stats lacks $key"; done
"$tessera" mesh info cube.obj | grep -q "genus" || fail "info without --stats prints a table"

# Conversions: every format and back to OBJ, the figures unchanged (STL is triangulated: 12 faces, 18 edges).
"$tessera" mesh convert cube.obj -o cube.ply
"$tessera" mesh convert cube.ply -o cube_ascii.ply --ascii
head -c 40 cube_ascii.ply | grep -q "format ascii" || fail "--ascii writes an ASCII PLY"
"$tessera" mesh convert cube_ascii.ply -o cube.off
"$tessera" mesh convert cube.off -o cube.stl
"$tessera" mesh convert cube.stl -o cube_ascii.stl --ascii
"$tessera" mesh convert cube_ascii.stl -o back.obj
for f in cube.ply cube_ascii.ply cube.off back.obj; do
  "$tessera" mesh info "$f" --stats | grep -qx "volume=1" || fail "$f keeps the volume"
done
for f in cube.ply cube_ascii.ply cube.off; do
  [ "$("$tessera" mesh info "$f" --stats | grep -E '^(vertices|faces|euler)=' | tr '\n' ' ')" = "vertices=8 faces=6 euler=2 " ] ||
    fail "$f keeps the counts"
done
[ "$("$tessera" mesh info back.obj --stats | grep -E '^(vertices|faces|edges|euler)=' | tr '\n' ' ')" = \
  "vertices=8 faces=12 edges=18 euler=2 " ] || fail "the STL round trip welds a closed triangle cube"

# Processing commands.
"$tessera" mesh triangulate cube.obj -o tri.obj
"$tessera" mesh info tri.obj --stats | grep -qx "faces=12" || fail "triangulate splits 6 quads into 12 triangles"
"$tessera" mesh normals cube.obj -o normals.obj --weighting angle
[ "$(grep -c '^vn ' normals.obj)" = 8 ] || fail "normals writes one vn per vertex"
"$tessera" mesh smooth tri.obj -o smooth.ply --method taubin --iterations 5 --quiet
"$tessera" mesh smooth tri.obj -o smooth.off --method laplacian --iterations 3 --lambda 0.3
"$tessera" mesh smooth tri.obj -o smooth.stl --method cotangent --iterations 2
[ -s smooth.ply ] && [ -s smooth.off ] && [ -s smooth.stl ] || fail "smooth writes its output"

# --stats on every subcommand: the output's vertices and faces, the phases, total_s.
for args in "convert cube.obj -o st1.ply" "normals cube.obj -o st2.obj" "triangulate cube.obj -o st3.obj" \
  "smooth tri.obj -o st4.obj --method laplacian --iterations 1" "weld cube.obj -o st5.obj"; do
  # shellcheck disable=SC2086
  stats=$("$tessera" mesh $args --stats)
  for key in vertices faces read_s compute_s write_s total_s; do
    grep -q "^$key=" <<<"$stats" || fail "mesh $args --stats lacks $key: $stats"
  done
done
"$tessera" mesh triangulate cube.obj -o st6.obj --stats | grep -qx "triangles=12" || fail "triangulate --stats"
# Enum options list their names, never the numbers behind them.
for sub in normals smooth subdivide; do
  "$tessera" mesh $sub --help | grep -q -- '->' && fail "mesh $sub --help shows internal enum values"
done
"$tessera" mesh smooth --help | grep -q "laplacian" || fail "mesh smooth --help lists the methods"
# weld: six separate quads (a soup of the cube's faces, 24 vertices) become the 8-vertex closed cube.
awk '/^v /{v[++n]=$0} /^f /{for(i=2;i<=5;i++){print v[$i]; } print "f " 4*k+1 " " 4*k+2 " " 4*k+3 " " 4*k+4; k++}' \
  cube.obj >soup.obj
[ "$(grep -c '^v ' soup.obj)" = 24 ] || fail "the soup has 24 vertices"
stats=$("$tessera" mesh weld soup.obj -o welded.obj --stats)
grep -qx "merged_vertices=16" <<<"$stats" || fail "weld merges 16 of 24 vertices: $stats"
"$tessera" mesh info welded.obj --stats | grep -qx "volume=1" || fail "the welded soup is the closed unit cube"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1e-7 0\nv 2 0 0\nf 1 2 3\nf 4 5 3\n' >gap.obj
"$tessera" mesh weld gap.obj -o gap0.obj --stats | grep -qx "vertices=5" || fail "weld without tolerance is exact"
"$tessera" mesh weld gap.obj -o gap1.obj --tolerance 1e-6 --stats | grep -qx "vertices=4" || fail "weld --tolerance"
# PLY: float32 by default, --double on request.
grep -a -q "property float x" st1.ply || fail "PLY coordinates are float by default"
"$tessera" mesh convert cube.obj -o double.ply --double
grep -a -q "property double x" double.ply || fail "--double writes double coordinates"

# Spot (Keenan Crane): 2930 vertices, face-varying uvs (3225 vt). Every attribute a format can hold is carried.
spot="${TESSERA_SHARED_DATA:-}/meshes/spot/spot_triangulated.obj"
if [ -f "$spot" ]; then
  "$tessera" mesh convert "$spot" -o spot.ply 2>err.txt
  [ ! -s err.txt ] || fail "PLY holds uvs: no warning expected: $(cat err.txt)"
  grep -a -q "property float s" spot.ply && grep -a -q "property float t" spot.ply || fail "spot.ply has no s t"
  # PLY holds per-vertex uvs: one vertex per distinct v/vt pair of the OBJ's faces.
  pairs=$(awk '/^f /{for(i=2;i<=NF;i++) print $i}' "$spot" | sort -u | wc -l)
  "$tessera" mesh info spot.ply --stats | grep -qx "vertices=$pairs" || fail "spot.ply should have $pairs vertices"
  "$tessera" mesh convert "$spot" -o spot.off
  head -1 spot.off | grep -qx "STOFF" || fail "OFF keeps the uvs (STOFF)"
  "$tessera" mesh convert spot.ply -o spot_from_ply.obj
  "$tessera" mesh convert spot.off -o spot_from_off.obj
  PYTHONPATH="$cli_dir" /usr/bin/python3 - "$spot" spot_from_ply.obj spot_from_off.obj <<'EOF'
import sys
from obj_corners import obj_corners
ref = obj_corners(sys.argv[1])
for path in sys.argv[2:]:
    got = obj_corners(path)
    assert len(got) == len(ref), path
    worst = max(abs(a - b) for r, g in zip(ref, got) for a, b in zip(r, g))
    assert worst < 1e-6, f"{path}: a corner's position or uv moved by {worst}"
EOF
  "$tessera" mesh convert "$spot" -o spot_again.obj
  [ "$(grep -c '^vt ' spot_again.obj)" = "$(grep -c '^vt ' "$spot")" ] || fail "OBJ writes each distinct uv once"
  "$tessera" mesh convert "$spot" -o spot.stl 2>err.txt
  grep -q "warning: spot.stl: the format cannot hold texture coordinates" err.txt || fail "STL warns: $(cat err.txt)"
  "$tessera" mesh info "$spot" --progress plain 2>err.txt >/dev/null
  grep -q "read spot_triangulated.obj: started" err.txt && grep -q "read spot_triangulated.obj: done" err.txt ||
    fail "reading shows progress lines: $(cat err.txt)"
else
  echo "skipped the Spot checks: no shared data in TESSERA_SHARED_DATA"
fi
# Errors: exit 1 with the place, and no output file left behind.
set +e
"$tessera" mesh info missing.obj 2>err.txt
rc=$?
set -e
[ $rc = 1 ] || fail "a missing file exits 1 (got $rc)"
grep -q "tessera: error: cannot open 'missing.obj'" err.txt || fail "a missing file is named: $(cat err.txt)"

printf 'v 0 0 0\nv 1 0 0\nv 1 x 0\nf 1 2 3\n' >bad.obj
set +e
"$tessera" mesh convert bad.obj -o bad.ply 2>err.txt
rc=$?
set -e
[ $rc = 1 ] || fail "a malformed line exits 1 (got $rc)"
grep -q "bad.obj:3: expected a vertex coordinate" err.txt || fail "the message names file:line: $(cat err.txt)"
[ ! -e bad.ply ] || fail "no output file is left after an error"
ls | grep -q "tmp-" && fail "no temporary file is left after an error"

set +e
"$tessera" mesh smooth cube.obj -o s.obj --method bogus --iterations 1 2>/dev/null
rc=$?
set -e
[ $rc = 2 ] || fail "an unknown --method is a usage error (exit 2, got $rc)"
set +e
"$tessera" mesh convert cube.obj -o cube.xyz 2>err.txt
rc=$?
set -e
[ $rc = 1 ] && grep -q "unknown mesh format" err.txt || fail "an unknown extension is reported"
echo "mesh CLI: ok"
