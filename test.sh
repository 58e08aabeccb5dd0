#!/usr/bin/env bash
# Builds granasym and runs the whole test suite (installs missing packages).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$root/scripts/install_deps.sh"
# Warnings are errors here (GRANASYM_WERROR): CI fails on a new warning in
# the project's code; third-party headers are system headers and never warn.
"$root/scripts/build.sh" -DGRANASYM_WERROR=ON
cd "${GRANASYM_BUILD_DIR:-$root/build}"
ctest --output-on-failure --timeout 900
