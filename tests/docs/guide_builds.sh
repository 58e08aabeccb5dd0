#!/usr/bin/env bash
# Builds the user guide (docs/guide: Sphinx with MyST) into HTML:
#   guide_builds.sh GUIDE_DIR OUT_DIR GRANASYM
# (GRANASYM: the program, whose `granasym keys` tables the reference page
# includes, generated into OUT_DIR/keys; docs/guide/conf.py)
# with warnings as errors (-W), nitpicky (-n): a link to a page, a heading
# anchor (myst_heading_anchors) or a repository file that does not exist, an
# image that cannot be read, a page left out of every toctree and a
# literalinclude whose markers moved all fail the build. The Markdown files
# outside the guide that link into it (README.md, docs/*.md) are checked
# too: every relative link and image names a file that exists.
set -euo pipefail
guide="$1" out="$2"
export GRANASYM="$3"
if ! command -v sphinx-build >/dev/null 2>&1; then
  echo "FAIL: sphinx-build not found: install python3-sphinx and python3-myst-parser" \
       "(scripts/install_deps.sh)"
  exit 1
fi
root="$(cd "$guide/../.." && pwd)"
broken=0
for page in "$root/README.md" "$root"/docs/*.md; do
  # [text](target) and ![alt](target) without a scheme; the anchor dropped.
  while IFS= read -r target; do
    file="${target%%#*}"
    [ -z "$file" ] && continue
    if [ ! -e "$(dirname "$page")/$file" ]; then
      echo "FAIL: ${page#"$root"/}: the link to '$target' names no file"
      broken=1
    fi
  done < <(grep -oE '\]\([^) ]+\)' "$page" | sed -E 's/^\]\((.*)\)$/\1/' | grep -vE '^[a-z]+:')
done
[ "$broken" -eq 0 ] || exit 1
rm -rf "$out"
start=$(date +%s%N)
sphinx-build -W -n --keep-going -q -b html -d "$out/doctrees" "$guide" "$out/html"
ms=$(( ($(date +%s%N) - start) / 1000000 ))
[ -s "$out/html/index.html" ] || { echo "FAIL: no index.html in $out/html"; exit 1; }
# The reference holds every kind's generated tables: each key of each.
keys=0
for kind in scene stage programme figures calibration; do
  [ -s "$out/keys/$kind.md" ] || { echo "FAIL: no generated $out/keys/$kind.md"; exit 1; }
  while IFS= read -r key; do
    keys=$((keys + 1))
    grep -qF "<span class=\"pre\">$key</span>" "$out/html/reference.html" ||
      { echo "FAIL: reference.html lacks the $kind key '$key'"; exit 1; }
  done < <(sed -nE 's/^\| `([^`]+)` \|.*/\1/p' "$out/keys/$kind.md" | sort -u)
done
[ "$keys" -gt 100 ] || { echo "FAIL: only $keys keys in the generated tables"; exit 1; }
if grep -q "granasym-keys" "$out/html/reference.html"; then
  echo "FAIL: reference.html keeps a granasym-keys fence"; exit 1
fi
pages=$(find "$out/html" -name '*.html' ! -name 'genindex.html' ! -name 'search.html' | wc -l)
echo "PASS: user guide built in ${ms} ms: $pages pages in $out/html/index.html, $keys generated key rows"
