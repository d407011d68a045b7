#!/usr/bin/env bash
# Installs the Debian 12 packages Tessera needs, if any are missing: `install-deps.sh demo` only what the library and
# the `tessera` command need to build (make demo), `install-deps.sh` (or `all`) also the tests', the benchmarks' and
# the reference peers' (make test, make bench).
# Idempotent and quiet when everything is there; uses sudo when not run as root.
set -euo pipefail

demo_packages=(
  # build
  cmake ninja-build g++ pkg-config
  # libraries
  libglm-dev libstb-dev libtbb-dev nlohmann-json3-dev libcli11-dev libfmt-dev zlib1g-dev libgif-dev libjpeg62-turbo-dev
  # the window of tessera sketch and tessera view (without it they run headless only)
  libsdl2-dev
  # GLSL programs: glslang, the Khronos reference compiler, parses and type-checks them (without it they are left out)
  glslang-dev
)
test_packages=(
  # tests and benchmarks
  libgtest-dev libgmock-dev libbenchmark-dev python3 python3-numpy librsvg2-bin python3-pil ffmpeg
  # reference peers (tests and benchmarks only, never the implementation)
  libosd-dev libtinyobjloader-dev python3-skimage python3-vtk9 libosmesa6-dev libembree-dev povray
  # a virtual X server: Debian's VTK needs a display for its volume ray-cast mapper (bench_volume under xvfb-run)
  xvfb xauth
  # the real-window tests of tessera sketch and tessera view: input sent by xdotool, the window grabbed by import
  xdotool imagemagick
  # the Python package: built with pybind11, installed into a virtual environment, tested with pytest
  pybind11-dev python3-dev python3-venv python3-setuptools python3-pytest
  # the Python tests: mypy checks the type stubs, nbclient and ipykernel run the tour notebook
  python3-mypy python3-nbclient python3-ipykernel
  # render farms: a real one-node Slurm cluster (tests/cli/slurm.sh) and Open MPI's mpirun (tessera ... --mpi)
  slurm-wlm munge libopenmpi-dev openmpi-bin
  # glslangValidator, the reference compiler's command line: the GLSL tests check the shipped shaders with it
  glslang-tools
  # the sanitizer build (make asan): clang's UBSan sees what GCC's does not, and libFuzzer comes with clang
  clang libclang-rt-14-dev
  # the format and lint checks of make test
  clang-format clang-tidy
)

case "${1:-all}" in
  demo) packages=("${demo_packages[@]}") ;;
  all) packages=("${demo_packages[@]}" "${test_packages[@]}") ;;
  *) echo "usage: install-deps.sh [demo|all]" >&2; exit 2 ;;
esac

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
