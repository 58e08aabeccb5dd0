#!/usr/bin/env bash
# Configures and builds granasym (Release) in build/ (or $GRANASYM_BUILD_DIR).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${GRANASYM_BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"
generator=()
if command -v ninja >/dev/null 2>&1 && [ ! -f "$build/Makefile" ]; then generator=(-G Ninja); fi
# ccache, when installed (scripts/install_deps.sh installs it), makes a
# rebuild of unchanged sources nearly free; GRANASYM_CCACHE=OFF disables it.
launcher=()
if [ "${GRANASYM_CCACHE:-ON}" != OFF ] && command -v ccache >/dev/null 2>&1; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# Built where it runs: tune for this machine (GRANASYM_NATIVE=OFF to disable).
# Extra arguments go to cmake (e.g. -DGRANASYM_WERROR=ON, as test.sh does).
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DGRANASYM_NATIVE="${GRANASYM_NATIVE:-ON}" "${launcher[@]}" "$@" >/dev/null
cmake --build "$build" --parallel "$jobs"
