#!/usr/bin/env bash
# Is the C++ tree formatted by .clang-format? Lists every file that is not
# and exits 1; with --fix, formats them in place. Uses Debian 12's
# clang-format (14), which scripts/install_deps.sh installs: another version
# formats some constructs differently, so it is named, not guessed.
#
#   scripts/check_format.sh          # check (the test suite runs this)
#   scripts/check_format.sh --fix    # format the tree
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
fix=0
case "${1:-}" in
  "") ;;
  --fix) fix=1 ;;
  *) echo "check_format.sh: unknown argument '$1' (valid: --fix)" >&2; exit 2 ;;
esac
format="${CLANG_FORMAT:-clang-format-14}"
command -v "$format" >/dev/null 2>&1 ||
  { echo "check_format.sh: '$format' not found; scripts/install_deps.sh installs clang-format" >&2; exit 2; }
cd "$root"
# The project's own sources: git's list in a clone, the source folders otherwise.
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files -- '*.cc' '*.h')
else
  mapfile -t files < <(find app analysis bench calibration common constitutive dem python study tests \
                         -name '*.cc' -o -name '*.h' | sort)
fi
[[ ${#files[@]} -gt 0 ]] || { echo "check_format.sh: no C++ files found under $root" >&2; exit 2; }
if [[ $fix == 1 ]]; then
  "$format" -i "${files[@]}"
  echo "formatted ${#files[@]} files"
  exit 0
fi
# One clang-format for the whole list; its warnings name the files.
mapfile -t bad < <("$format" --dry-run "${files[@]}" 2>&1 |
                   sed -n 's/^\(.*\):[0-9]*:[0-9]*: \(warning\|error\): .*/\1/p' | sort -u)
if [[ ${#bad[@]} -gt 0 ]]; then
  echo "not formatted by .clang-format (${#bad[@]} of ${#files[@]} files):"
  printf '  %s\n' "${bad[@]}"
  echo "fix with: scripts/check_format.sh --fix"
  exit 1
fi
echo "PASS: all ${#files[@]} C++ files formatted by .clang-format"
