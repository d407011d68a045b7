#!/usr/bin/env bash
# tessera mesh: info --stats on a hand-written cube, conversions through every format and back, normals, smoothing,
# triangulation, and the error paths (missing file, malformed line, usage errors).
# $1 = the tessera binary, $2 = a scratch folder.
set -euo pipefail
tessera=$1
dir=$2
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
[ "$got" = "$expected" ] || fail "info --stats of the cube: got
$got"
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
