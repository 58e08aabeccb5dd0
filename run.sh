#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the default scene
# (the paper's 150 000-sphere sample along ψ_ε = 0° to 1000 kPa).
# Results: out/ncl_default.h5 and out/ncl_default.csv.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
mkdir -p "$root/out"
scene="${1:-$root/studies/scenes/ncl_default.toml}"
name="$(basename "$scene" .toml)"
"$root/build/app/granasym" dem run "$scene" --out "$root/out/$name.h5"
"$root/build/app/granasym" export "$root/out/$name.h5" --csv "$root/out/$name.csv"
