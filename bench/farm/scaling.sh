#!/usr/bin/env bash
# Parallel efficiency of Tessera's farm routes on this machine (docs/farm.md, "Measurements"): an animation and one
# large frame rendered by 1 and by 2 MPI ranks of one thread each, a CT volume split into slabs, the cost of a farm
# task around a one-second frame (process start, scene load, write, manifest), and the per-tile and compositing costs
# the 100-node model uses. Each figure is the best of three runs. Usage: bench/farm/scaling.sh [path/to/tessera]
set -euo pipefail
tessera="${1:-build/release/apps/tessera/tessera}"
tessera="$(cd "$(dirname "$tessera")" && pwd)/$(basename "$tessera")"
data="${TESSERA_SHARED_DATA:-$(cd "$(dirname "$0")/../../.." && pwd)/shared/data}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

# Wall seconds of a command, best of three.
best() {
  local b=""
  for _ in 1 2 3; do
    local t0 t1
    t0=$(date +%s.%N)
    "$@" > /dev/null 2>&1
    t1=$(date +%s.%N)
    b=$(python3 -c "t = $t1 - $t0; b = '$b'; print(min(t, float(b)) if b else t)")
  done
  echo "$b"
}
# "wall compute": the best of five of the whole mpirun (launch, MPI_Init, reading, rendering, writing) and of rank
# 0's compute_s (the rendering and compositing, from --stats).
measure() {
  local wall="" compute=""
  for _ in 1 2 3 4 5; do
    local t0 t1 c
    t0=$(date +%s.%N)
    c=$("$@" --stats 2> /dev/null | sed -n 's/^compute_s=//p')
    t1=$(date +%s.%N)
    wall=$(python3 -c "t = $t1 - $t0; b = '$wall'; print(min(t, float(b)) if b else t)")
    compute=$(python3 -c "t = $c; b = '$compute'; print(min(t, float(b)) if b else t)")
  done
  echo "$wall $compute"
}
row() { printf '%-52s %15s %15s %17s\n' "$@"; }
# One workload on 1 and on 2 ranks: wall and compute seconds, and the efficiency of each.
scale() {
  local name="$1"
  shift
  read -r w1 c1 <<< "$(measure mpirun -n 1 "$tessera" "$@")"
  read -r w2 c2 <<< "$(measure mpirun -n 2 "$tessera" "$@")"
  row "$name" "$(printf '%.2f / %.2f' "$w1" "$c1")" "$(printf '%.2f / %.2f' "$w2" "$c2")" \
    "$(python3 -c "print(f'{$w1 / (2 * $w2):.3f} / {$c1 / (2 * $c2):.3f}')")"
}

row "workload (1 thread per rank)" "1 rank wall/cmp" "2 ranks" "efficiency wall/cmp"
scale "animation: whitted-moving 24 frames 320x240, 8 spp" render whitted-moving --frames 0:23 -o a/f_%04d.png \
  --size 320x240 --spp 8 --threads 1 --quiet --mpi
scale "one frame: 960x720, 8 spp (16 tiles per rank)" render whitted-moving --frame 12 -o f.png --size 960x720 --spp 8 \
  --threads 1 --quiet --mpi
if [ -f "$data/volumes/foot_256x256x256_uint8.mhd" ]; then
  scale "volume: CT foot 256^3, 768x768, slabs + binary swap" volume render \
    "$data/volumes/foot_256x256x256_uint8.mhd" -o v.png --size 768x768 --preset ct-bone --threads 1 --quiet --mpi
  mpirun -n 2 "$tessera" volume render "$data/volumes/foot_256x256x256_uint8.mhd" -o v.png --size 768x768 \
    --preset ct-bone --threads 1 --quiet --mpi --stats | grep -E '^(read_s|compute_s|composite_s)=' | tr '\n' ' '
  echo
else
  echo "note: $data/volumes/foot_256x256x256_uint8.mhd is absent: no volume figure"
fi
launch=$(best mpirun -n 2 true)
echo "mpirun -n 2 of a program that does nothing: $launch s"

# A farm task around a frame of about one second: everything that is not rendering, as a share of it.
"$tessera" render whitted-moving --frame 7 --tile 0/1 -o task/f_%04d.png --size 400x300 --spp 8 --threads 1 --stats \
  --quiet > task.txt
python3 - task.txt <<'PY'
import sys
s = dict(line.strip().split("=", 1) for line in open(sys.argv[1]))
compute, total = float(s["compute_s"]), float(s["total_s"])
print(f"farm task: render {compute:.3f} s, everything else {total - compute:.4f} s in-process "
      f"({100 * (total - compute) / compute:.2f}% of the frame)")
PY
start=$(best "$tessera" render whitted-moving --frame 7 -o tiny.png --size 8x8 --spp 1 --threads 1 --quiet)
echo "farm task: a whole tessera process for an 8x8 frame (start, scene, write): $start s"

# Per-tile cost: one 256x192 frame as 1 tile and as 192 one-row tiles, on 2 ranks.
few=$(best mpirun -n 2 "$tessera" render whitted-moving --frame 3 -o t1.png --size 256x192 --spp 4 --threads 1 --mpi \
  --tiles 2 --quiet)
many=$(best mpirun -n 2 "$tessera" render whitted-moving --frame 3 -o t2.png --size 256x192 --spp 4 --threads 1 --mpi \
  --tiles 192 --quiet)
python3 -c "print(f'per-tile cost (2 ranks): {($many - $few) / 190 * 1000:.3f} ms ({$few:.3f} s with 2 tiles, {$many:.3f} s with 192)')"
