#!/usr/bin/env bash
# Configures and builds granasym (Release) in build/ (or $GRANASYM_BUILD_DIR).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${GRANASYM_BUILD_DIR:-$root/build}"
jobs="$(nproc 2>/dev/null || echo 2)"
generator=()
if command -v ninja >/dev/null 2>&1 && [ ! -f "$build/Makefile" ]; then generator=(-G Ninja); fi
# Built where it runs: tune for this machine (GRANASYM_NATIVE=OFF to disable).
cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DGRANASYM_NATIVE="${GRANASYM_NATIVE:-ON}" "$@" >/dev/null
cmake --build "$build" --parallel "$jobs"
