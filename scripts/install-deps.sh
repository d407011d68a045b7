#!/usr/bin/env bash
# Installs the Debian 12 packages Tessera's build, tests and benchmarks need, if any are missing.
# Idempotent and quiet when everything is there; uses sudo when not run as root.
set -euo pipefail

packages=(
  # build
  cmake ninja-build g++ pkg-config
  # libraries
  libglm-dev libstb-dev libtbb-dev nlohmann-json3-dev libcli11-dev libfmt-dev zlib1g-dev
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev python3 librsvg2-bin
  # reference peers (tests and benchmarks only, never the implementation)
  libosd-dev libtinyobjloader-dev python3-skimage python3-vtk9 libosmesa6-dev libembree-dev povray
  # a virtual X server: Debian's VTK needs a display for its volume ray-cast mapper (bench_volume under xvfb-run)
  xvfb xauth
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}" >&2
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
