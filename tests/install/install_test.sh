#!/usr/bin/env bash
# Installs the build tree into a scratch prefix, then configures and builds tests/install/consumer against it (the
# README example, and the installed umbrella header alone), checks `tessera --version`, and configures
# tests/install/subdirectory, which add_subdirectory()s the source tree with GoogleTest hidden (configure only:
# building would compile Tessera once more).
# Usage: install_test.sh BUILD_DIR SOURCE_DIR SCRATCH_DIR
set -euo pipefail
build=$1 source=$2 scratch=$3
rm -rf "$scratch"
cmake --install "$build" --prefix "$scratch/prefix" >/dev/null
cmake -S "$source/tests/install/consumer" -B "$scratch/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$scratch/prefix" >/dev/null
cmake --build "$scratch/consumer" >/dev/null
(cd "$scratch" && "$scratch/consumer/consumer")
"$scratch/consumer/umbrella"

# `tessera --version`: the project's version, the configured commit, and the SIMD level that /proc/cpuinfo's flags
# give (core's simd_level: AVX-512 F+BW+VL+DQ, else AVX2+FMA, else baseline).
version=$("$scratch/prefix/bin/tessera" --version)
echo "$version"
level=baseline
if [ -r /proc/cpuinfo ]; then
  flags=" $(grep -m1 '^flags' /proc/cpuinfo | cut -d: -f2) "
  has() { case "$flags" in *" $1 "*) return 0 ;; *) return 1 ;; esac; }
  if has avx2 && has fma; then level=avx2; fi
  if [ $level = avx2 ] && has avx512f && has avx512bw && has avx512vl && has avx512dq; then level=avx512; fi
fi
project_version=$(sed -n 's/^project(tessera VERSION \([0-9.]*\).*/\1/p' "$source/CMakeLists.txt")
# The commit as configured (later commits show after the next CMake run): `git describe`'s one word (a short hash,
# with "-dirty" when the tree had changes) in a checkout, else unknown.
hash=$(sed -n 's/^#define TESSERA_GIT_HASH "\(.*\)"$/\1/p' "$build/include/tessera/version.hpp")
if [ -e "$source/.git" ] && ! [[ $hash =~ ^[0-9A-Za-z._-]+$ && $hash != unknown ]]; then
  echo "install_test: configured git hash '$hash' is not what git describe prints" >&2
  exit 1
fi
if [ "$version" != "tessera $project_version (git $hash, $level)" ]; then
  echo "install_test: expected 'tessera $project_version (git $hash, $level)'" >&2
  exit 1
fi

cmake -S "$source/tests/install/subdirectory" -B "$scratch/subdirectory" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DTESSERA_SOURCE_DIR="$source" -DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON --no-warn-unused-cli >/dev/null
echo "install_test: a project that add_subdirectory()s Tessera configures without GoogleTest"
