#!/usr/bin/env bash
# Eigen reaches the project's code only through constitutive/eigen.h, which
# silences GCC 12's AVX-512 false positives around Eigen's headers (a direct
# <Eigen/...> include before it would bring them back into the build).
set -euo pipefail
root="$1"
cd "$root"
direct=$(grep -rlE '^\s*#\s*include\s*[<"](unsupported/)?Eigen/' \
           app analysis bench calibration common constitutive dem study tests \
           --include='*.cc' --include='*.h' | grep -v '^constitutive/eigen\.h$' || true)
if [ -n "$direct" ]; then
  echo "FAIL: these files include Eigen directly; include \"constitutive/eigen.h\" instead:"
  echo "$direct"
  exit 1
fi
grep -q '#include <Eigen/Core>' constitutive/eigen.h || { echo "FAIL: constitutive/eigen.h includes no Eigen"; exit 1; }
echo "PASS: Eigen is included only through constitutive/eigen.h"
