#!/usr/bin/env bash
# Builds granasym and runs the whole test suite (installs missing packages).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
cd "${GRANASYM_BUILD_DIR:-$root/build}"
ctest --output-on-failure --timeout 900
