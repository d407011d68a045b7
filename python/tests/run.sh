#!/usr/bin/env bash
# The Python package's tests as a user meets it: a fresh virtual environment (Debian's packages visible, nothing from
# PyPI), `pip install --no-build-isolation` of python/ against the configured build folder, then pytest on the
# installed package, from a folder outside the source tree.
#   run.sh BUILD_DIR SCRATCH TESSERA_CLI [PYTHON]
set -euo pipefail
build=$(cd "$1" && pwd) scratch=$2 cli=$3 python=${4:-/usr/bin/python3}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$scratch" && mkdir -p "$scratch"
"$python" -m venv --system-site-packages "$scratch/venv"
TESSERA_BUILD_DIR="$build" "$scratch/venv/bin/pip" install --quiet --no-build-isolation --no-index "$here/.." \
  >"$scratch/pip.log" 2>&1 || { cat "$scratch/pip.log"; exit 1; }
cd "$scratch"
export TESSERA_CLI=$cli
exec "$scratch/venv/bin/python" -m pytest -q -p no:cacheprovider "$here"
