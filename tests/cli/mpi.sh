#!/usr/bin/env bash
# Real mpirun ranks on this machine (Open MPI, --oversubscribe): `render --mpi` of an animation and of one frame in
# tiles gives the bytes of a one-process render for 1 to 4 ranks, and `volume render --mpi` (slabs of z composited by
# binary swap) is the one-process picture within 1/255 (early ray termination off on both, as each brick applies it
# to its own opacity), and `volume isosurface --mpi` (slabs welded on rank 0) is the one-process mesh. Exits 77 (skipped) when Tessera was built without MPI or mpirun is missing.
set -euo pipefail
tessera="$1"
scratch="$2"
rm -rf "$scratch" && mkdir -p "$scratch"
cd "$scratch"
fail() { echo "FAIL: $*"; exit 1; }
command -v mpirun > /dev/null || { echo "SKIP: mpirun is not installed (Debian: openmpi-bin)"; exit 77; }
if "$tessera" render whitted -o probe.png --size 8x8 --mpi 2>&1 | grep -q "built without MPI"; then
  echo "SKIP: this tessera was built without MPI (Debian: libopenmpi-dev)"
  exit 77
fi
# What CI needs to run ranks as root on a small machine, set here rather than in the user's environment.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
run() { timeout 300 mpirun -n "$@"; }

# An animation (whole frames per rank) and one frame in tiles, against one process.
"$tessera" render whitted-moving --frames 3:8 -o local/f_%04d.png --size 64x48 --spp 3 --quiet
"$tessera" render whitted-moving --frame 5 -o local/one.png --size 90x70 --spp 4 --quiet
for n in 1 2 3 4; do
  run "$n" "$tessera" render whitted-moving --frames 3:8 -o "mpi$n/f_%04d.png" --size 64x48 --spp 3 --mpi --threads 1 \
    --quiet
  for f in 3 4 5 6 7 8; do cmp "mpi$n/f_000$f.png" "local/f_000$f.png" || fail "$n ranks: frame $f differs"; done
  run "$n" "$tessera" render whitted-moving --frame 5 -o "mpi$n/one.png" --size 90x70 --spp 4 --mpi --threads 1 \
    --stats > "stats$n.txt"
  cmp "mpi$n/one.png" local/one.png || fail "$n ranks: the tiled frame differs"
  grep -q "^ranks=$n$" "stats$n.txt" && grep -q "^tiles=$((16 * n))$" "stats$n.txt" || fail "$(cat "stats$n.txt")"
done
# --skip-existing on rank 0's word, and a movie in frame order whatever order the frames finish in.
run 2 "$tessera" render whitted-moving --frames 3:8 -o mpi2/f_%04d.png --size 64x48 --spp 3 --mpi --skip-existing \
  --stats --quiet > skip.txt
grep -q '^skipped=6$' skip.txt || fail "skip: $(cat skip.txt)"
"$tessera" render whitted-moving --frames 0:5 -o local.gif --size 40x30 --spp 1 --quiet
run 3 "$tessera" render whitted-moving --frames 0:5 -o mpi.gif --size 40x30 --spp 1 --mpi --quiet
cmp mpi.gif local.gif || fail "the movie differs"

# Volumes: slabs of z, sort-last. A real CT head when the shared data is there, and a procedural volume.
volumes=(gyroid:40)
head="${TESSERA_SHARED_DATA:-}/volumes/headsq_64x64x93_int16le.mhd"
if [ -f "$head" ]; then volumes+=("$head"); else echo "note: $head is absent; the CT head is not rendered"; fi
for volume in "${volumes[@]}"; do
  "$tessera" volume render "$volume" -o v1.pfm --size 96x80 --termination 1 --quiet
  for n in 2 3 4; do
    run "$n" "$tessera" volume render "$volume" -o "v$n.pfm" --size 96x80 --termination 1 --mpi --threads 1 --quiet
    /usr/bin/python3 - v1.pfm "v$n.pfm" <<'PY' || fail "$volume on $n ranks differs by more than 1/255"
import struct, sys
def pfm(path):
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    w, h = map(int, parts[1].split())
    return struct.unpack(f"<{w * h * 3}f", parts[3][: w * h * 12])
a, b = pfm(sys.argv[1]), pfm(sys.argv[2])
worst = max(abs(x - y) for x, y in zip(a, b))
assert len(a) == len(b) and worst <= 1 / 255, worst
assert max(a) > 0.1, "the picture is empty"
PY
  done
done
# Iso-surfaces: slabs of z extracted in the whole volume's coordinates and welded on rank 0 give the one-process mesh:
# the same vertices (as written, bit for bit) and the same triangles, classic and topological.
for volume in "${volumes[@]}"; do
  for mode in "" --topological; do
    "$tessera" volume isosurface "$volume" -o i1.obj $mode --quiet
    for n in 2 3 4; do
      run "$n" "$tessera" volume isosurface "$volume" -o "i$n.obj" $mode --mpi --threads 1 --quiet
      /usr/bin/python3 - i1.obj "i$n.obj" <<'PY' || fail "$volume $mode: the iso-surface on $n ranks differs"
import sys
def load(path):
    vertices, faces = [], []
    for line in open(path):
        if line.startswith("v "):
            vertices.append(tuple(line.split()[1:4]))
        elif line.startswith("f "):
            faces.append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
    # A triangle by its corners' positions, rotated to start at the smallest (orientation kept).
    def key(f):
        c = [vertices[i] for i in f]
        k = c.index(min(c))
        return tuple(c[k:] + c[:k])
    return sorted(vertices), sorted(key(f) for f in faces)
a, b = load(sys.argv[1]), load(sys.argv[2])
assert len(a[0]) > 100 and a == b, (len(a[0]), len(b[0]), len(a[1]), len(b[1]))
PY
    done
  done
done

status() { set +e; "$@" > /dev/null 2>&1; echo $?; set -e; }
test "$(status run 2 "$tessera" volume render gyroid:20 -o m.png --mip --mpi)" != 0
test "$(status run 2 "$tessera" render whitted-moving --frame 1 --tile 0/2 -o t.png --mpi)" != 0
test ! -e m.png && test ! -e t.png
echo "mpi: ok"
