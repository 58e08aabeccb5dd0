#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the paper's
# programme (studies/programmes/paper.toml) at the small scale into
# out/paper-small/, calibrates the three models to its asymptotic states,
# draws the paper's figures and writes the report: out/paper-small/index.html.
# It also makes `import granasym` (the Python module) work for this user.
# Running it again computes only what is missing or changed.
#
#   ./run.sh                       the paper's programme, small scale
#   ./run.sh PROGRAMME.toml [SCALE] another programme, or another scale (tiny, small, medium, paper)
#   ./run.sh SCENE.toml            one DEM scene (out/SCENE.h5 and out/SCENE.csv)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
"$root/scripts/install_deps.sh"
"$root/scripts/build.sh"
# The Python module (python/, built when pybind11 and Python are found): its
# folder named in this user's site-packages (granasym.pth), so that
# `python3 -c "import granasym"` works from anywhere; remove that file to undo.
if compgen -G "$root/build/python/granasym*.so" >/dev/null && command -v python3 >/dev/null; then
  site="$(python3 -c 'import site; print(site.getusersitepackages())')"
  if [ "$(cat "$site/granasym.pth" 2>/dev/null)" != "$root/build/python" ]; then
    mkdir -p "$site"
    echo "$root/build/python" >"$site/granasym.pth"
    echo "run.sh: import granasym: $root/build/python named in $site/granasym.pth"
  fi
fi
mkdir -p "$root/out"
input="${1:-$root/studies/programmes/paper.toml}"
name="$(basename "$input" .toml)"
granasym="$root/build/app/granasym"
if grep -q '^\[study\]' "$input"; then
  scale="${2:-small}"
  out="$root/out/$name-$scale"
  "$granasym" study run "$input" --scale "$scale" --out "$out"
  # A model whose fit did not converge cleanly exits non-zero
  # (docs/guide/exit-statuses.md); its status is in the report, and the
  # figures and report follow.
  "$granasym" study calibrate "$out" ||
    echo "run.sh: not every model converged (see above and $out/calibration/*/fit_status.toml)"
  "$granasym" study figures "$out"
  "$granasym" study report "$out"
else
  "$granasym" dem run "$input" --out "$root/out/$name.h5"
  "$granasym" export "$root/out/$name.h5" --csv "$root/out/$name.csv"
fi
