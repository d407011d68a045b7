#!/usr/bin/env bash
# The umbrella header (cmake/tessera.hpp.in) lists every public header of every module: they are listed by hand.
set -euo pipefail
cd "$(dirname "$0")/../.."
status=0
for h in libs/*/include/tessera/*/*.hpp; do
  header=${h#libs/*/include/}
  grep -qF "#include \"$header\"" cmake/tessera.hpp.in || { echo "missing from cmake/tessera.hpp.in: $header"; status=1; }
done
exit $status
