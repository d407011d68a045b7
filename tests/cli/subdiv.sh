#!/usr/bin/env bash
# `tessera mesh subdivide` end to end: a cube OBJ through every scheme, face counts checked by counting `f ` lines,
# crease tags, the limit option, --stats, and clear errors (exit 1) and usage errors (exit 2).
# Usage: subdiv.sh TESSERA_BINARY SCRATCH_DIR
set -euo pipefail
bin=$1
dir=$2
cli_dir="$(cd "$(dirname "$0")" && pwd)"  # obj_corners.py
mkdir -p "$dir"

fail() {
  echo "subdiv.sh: $*" >&2
  exit 1
}
faces() { grep -c '^f ' "$1"; }
expect_faces() {  # FILE COUNT
  local n
  n=$(faces "$1")
  [ "$n" = "$2" ] || fail "$1: expected $2 faces, got $n"
}

cp "$(dirname "$0")/../data/cube.obj" "$dir/cube.obj"
# The same cube as 12 triangles, and open (no top face) for boundaries.
awk '/^v /{print} /^f /{print "f "$2" "$3" "$4; print "f "$2" "$4" "$5}' "$dir/cube.obj" >"$dir/cube_tris.obj"
grep -v '^f 5 6 7 8$' "$dir/cube.obj" >"$dir/open_box.obj"
# Creases (OpenSubdiv's tags, 0-based): the top ring infinitely sharp, one corner.
{ cat "$dir/cube.obj"; echo "t crease 2/1/0 4 5 10"; echo "t crease 2/1/0 5 6 10"; echo "t crease 2/1/0 6 7 10"
  echo "t crease 2/1/0 7 4 10"; echo "t corner 1/1/0 0 10"; } >"$dir/creased.obj"

"$bin" mesh subdivide "$dir/cube.obj" -o "$dir/cc.obj" --scheme catmull-clark --levels 2 --quiet
expect_faces "$dir/cc.obj" 96
"$bin" mesh subdivide "$dir/cube.obj" -o "$dir/mid.obj" --scheme midpoint --levels 1 --quiet
expect_faces "$dir/mid.obj" 24
"$bin" mesh subdivide "$dir/cube_tris.obj" -o "$dir/loop.obj" --scheme loop --levels 2 --quiet
expect_faces "$dir/loop.obj" 192
"$bin" mesh subdivide "$dir/cube_tris.obj" -o "$dir/loop_orig.obj" --scheme loop --loop-beta loop --quiet
expect_faces "$dir/loop_orig.obj" 48
"$bin" mesh subdivide "$dir/open_box.obj" -o "$dir/open.obj" --levels 2 --boundary edge-and-corner --quiet
expect_faces "$dir/open.obj" 80
"$bin" mesh subdivide "$dir/creased.obj" -o "$dir/creased_out.obj" --levels 1 --crease-method chaikin --quiet
expect_faces "$dir/creased_out.obj" 24
# The sharp corner (vertex 0) stays put.
[ "$(grep '^v ' "$dir/creased_out.obj" | head -1 | awk '{print ($2 == -1 && $3 == -1 && $4 == -1) ? "ok" : $0}')" = ok ] ||
  fail "the tagged corner moved"
"$bin" mesh subdivide "$dir/cube.obj" -o "$dir/limit.obj" --levels 1 --limit --quiet
expect_faces "$dir/limit.obj" 24

# --stats: key=value lines on stdout.
stats=$("$bin" mesh subdivide "$dir/cube.obj" -o "$dir/stats.obj" --levels 3 --stats --quiet)
grep -qx 'faces=384' <<<"$stats" || fail "--stats: expected faces=384, got: $stats"
grep -qx 'vertices=386' <<<"$stats" || fail "--stats: expected vertices=386, got: $stats"
grep -q '^seconds=' <<<"$stats" || fail "--stats: no seconds"
for key in levels=3 read_s compute_s write_s total_s; do
  grep -q "^$key" <<<"$stats" || fail "--stats lacks $key: $stats"
done
"$bin" mesh subdivide --help | grep -q -- '->' && fail "--help shows internal enum values"
"$bin" mesh subdivide --help | grep -q "catmull-clark" || fail "--help lists the schemes"

# Face-varying uvs are carried (OpenSubdiv's linear face-varying rule): two unit quads side by side, each with its
# own vt (a seam on the shared edge), uv = (x/2, y). Midpoint subdivision keeps positions linear, so every refined
# corner must still have uv = (x/2, y). Normals in the input give the output normals.
cat >"$dir/plane.obj" <<'OBJ'
v 0 0 0
v 1 0 0
v 2 0 0
v 0 1 0
v 1 1 0
v 2 1 0
vt 0 0
vt 0.5 0
vt 0.5 1
vt 0 1
vt 0.5 0
vt 1 0
vt 1 1
vt 0.5 1
vn 0 0 1
f 1/1/1 2/2/1 5/3/1 4/4/1
f 2/5/1 3/6/1 6/7/1 5/8/1
OBJ
"$bin" mesh subdivide "$dir/plane.obj" -o "$dir/plane_sub.obj" --scheme midpoint --levels 2 --quiet
expect_faces "$dir/plane_sub.obj" 32
[ "$(grep -c '^vn ' "$dir/plane_sub.obj")" -gt 0 ] || fail "normals are dropped"
PYTHONPATH="$cli_dir" /usr/bin/python3 - "$dir/plane_sub.obj" <<'EOF'
import sys
from obj_corners import obj_corners
corners = obj_corners(sys.argv[1])
for x, y, z, u, v in corners:
    assert abs(u - x / 2) < 1e-12 and abs(v - y) < 1e-12, (x, y, u, v)
assert len(corners) == 128, len(corners)
EOF
"$bin" mesh subdivide "$dir/plane.obj" -o "$dir/plane_cc.ply" --levels 1 --quiet 2>"$dir/err.txt"
[ ! -s "$dir/err.txt" ] || fail "PLY holds the uvs: no warning expected: $(cat "$dir/err.txt")"
grep -a -q "property float s" "$dir/plane_cc.ply" || fail "the subdivided PLY has no uvs"
if "$bin" mesh info --help >/dev/null 2>&1; then
  "$bin" mesh info "$dir/stats.obj" --stats | grep -qx 'faces=384' || fail "mesh info disagrees on the face count"
fi

# Issue 24, class 2: finite but huge coordinates (1e308) gave nan vertices with --limit (exit 0; Tessera then refused
# to read the file) and zero normals when the input has normals. Subdivision is affine: the result must be the unit
# cube's, times 1e308, with the same normals.
awk '/^v /{printf "v %.17g %.17g %.17g\n", $2*1e308, $3*1e308, $4*1e308} /^f /{print}' "$dir/cube.obj" >"$dir/huge.obj"
for mesh in cube huge; do
  { grep '^v ' "$dir/$mesh.obj"; echo "vn 0 0 1"; grep '^f' "$dir/$mesh.obj" | sed 's#\([0-9][0-9]*\)#\1//1#g'; } >"$dir/${mesh}_n.obj"
done
"$bin" mesh subdivide "$dir/cube.obj" -o "$dir/unit_limit.obj" --levels 2 --limit --quiet
"$bin" mesh subdivide "$dir/huge.obj" -o "$dir/huge_limit.obj" --levels 2 --limit --quiet
"$bin" mesh subdivide "$dir/cube_n.obj" -o "$dir/unit_n.obj" --levels 1 --quiet
"$bin" mesh subdivide "$dir/huge_n.obj" -o "$dir/huge_n_out.obj" --levels 1 --quiet
/usr/bin/python3 - "$dir" <<'PY' || fail "huge coordinates: the result is not the scaled unit result"
import math, sys
d = sys.argv[1]
def read(name, key):
    return [[float(x) for x in line.split()[1:4]] for line in open(f"{d}/{name}") if line.startswith(key + " ")]
for unit, huge, key, scale in (("unit_limit.obj", "huge_limit.obj", "v", 1e308), ("unit_limit.obj", "huge_limit.obj", "vn", 1),
                               ("unit_n.obj", "huge_n_out.obj", "v", 1e308), ("unit_n.obj", "huge_n_out.obj", "vn", 1)):
    a, b = read(unit, key), read(huge, key)
    assert len(a) == len(b) > 0, (unit, key, len(a), len(b))
    for p, q in zip(a, b):
        assert all(math.isfinite(y) and abs(y / scale - x) < 1e-9 for x, y in zip(p, q)), (huge, key, p, q)
PY

# Errors: exit 1 with a clear message; usage errors exit 2.
expect_error() {  # CODE PATTERN COMMAND...
  local code=$1 pattern=$2 status=0
  shift 2
  "$@" >"$dir/out.txt" 2>"$dir/err.txt" || status=$?
  [ "$status" = "$code" ] || fail "expected exit $code, got $status: $*"
  grep -qi -- "$pattern" "$dir/err.txt" || fail "expected '$pattern' in: $(cat "$dir/err.txt")"
}
expect_error 1 'triangle' "$bin" mesh subdivide "$dir/cube.obj" -o "$dir/x.obj" --scheme loop --quiet
expect_error 1 'tessera: error' "$bin" mesh subdivide "$dir/missing.obj" -o "$dir/x.obj" --quiet
expect_error 1 'no smooth limit' "$bin" mesh subdivide "$dir/cube.obj" -o "$dir/x.obj" --scheme midpoint --limit --quiet
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 2 1 3\n' >"$dir/nonmanifold.obj"
expect_error 1 'non-manifold' "$bin" mesh subdivide "$dir/nonmanifold.obj" -o "$dir/x.obj" --quiet
expect_error 2 'scheme' "$bin" mesh subdivide "$dir/cube.obj" -o "$dir/x.obj" --scheme butterfly
expect_error 2 'levels' "$bin" mesh subdivide "$dir/cube.obj" -o "$dir/x.obj" --levels 13
[ ! -e "$dir/x.obj" ] || fail "a failed run left an output file"
echo "subdiv.sh: all checks passed"
