#!/usr/bin/env bash
# Does a granasym binary still compute what it did? Runs the checks that a
# change meant to keep behaviour (a refactoring) must pass and writes the
# SHA-256 of every result file to OUT/hashes.txt:
#   - the default scene (studies/scenes/ncl_default.toml, 150 000 spheres,
#     about a minute on 2 cores) exported as CSV;
#   - the paper's programme at the tiny and small scales (about 8 minutes on
#     2 cores): every CSV, TSV and DAT file of the study folder outside its
#     cases (the state table, the calibration's tables and plot data, the
#     model runs, the figures' data and index);
#   - the rate study at the tiny scale: the same, with its rate_*.csv.
# Run it with the binary before and after the change and compare:
#
#   bench/behaviour_hashes.sh BINARY OUT [--skip-small] [--skip-scene]
#   diff OUT_BEFORE/hashes.txt OUT_AFTER/hashes.txt
#   bench/behaviour_hashes.sh --rehash OUT   # hash the folders of OUT again
#
# Files that carry wall times, hosts, paths or program versions (HDF5, TOML,
# logs, summaries, the report) are not hashed. Exit status 0 when every run
# finished, 2 on bad arguments.
set -euo pipefail
usage() { sed -n '2,21p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }
[[ $# -ge 2 ]] || { usage >&2; exit 2; }
rehash=0
if [[ "$1" == --rehash ]]; then rehash=1; BIN=""; else BIN="$(realpath "$1")"; fi
OUT="$2"; shift 2
small=1; scene=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --skip-small) small=0; shift ;;
    --skip-scene) scene=0; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "behaviour_hashes.sh: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
[[ $rehash == 1 || -x "$BIN" ]] ||
  { echo "behaviour_hashes.sh: '$BIN' is not an executable" >&2; exit 2; }
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
hash_study() {  # folder label
  local dir="$1" label="$2"
  (cd "$dir" && find . -path ./cases -prune -o -type f \( -name '*.csv' -o -name '*.tsv' -o -name '*.dat' \) -print |
     LC_ALL=C sort |
     while read -r f; do echo "$(sha256sum "$f" | cut -c1-64)  $label/${f#./}"; done)
}

mkdir -p "$OUT"
OUT="$(realpath "$OUT")"
if [[ $rehash == 1 ]]; then
  { [[ -f "$OUT/ncl_default.csv" ]] &&
      echo "$(sha256sum "$OUT/ncl_default.csv" | cut -c1-64)  ncl_default.csv"
    for label in paper-tiny rate-tiny paper-small; do
      [[ -d "$OUT/$label" ]] && hash_study "$OUT/$label" "$label"
    done; } > "$OUT/hashes.txt"
  echo "$(wc -l < "$OUT/hashes.txt") files hashed: $OUT/hashes.txt"
  exit 0
fi
log="$OUT/log.txt"
: > "$log"

study() {  # programme scale label
  local programme="$1" scale="$2" label="$3" dir="$OUT/$3"
  echo "== $label: study run $programme --scale $scale" | tee -a "$log"
  "$BIN" study run "$root/studies/programmes/$programme" --scale "$scale" --out "$dir" \
    --quiet >>"$log" 2>&1
  "$BIN" study calibrate "$dir" >>"$log" 2>&1 || echo "   (calibration reported failures)" | tee -a "$log"
  "$BIN" study figures "$dir" --data-only >>"$log" 2>&1
  hash_study "$dir" "$label" >> "$OUT/hashes.txt.part"
}

: > "$OUT/hashes.txt.part"
if [[ $scene == 1 ]]; then
  echo "== default scene" | tee -a "$log"
  "$BIN" dem run "$root/studies/scenes/ncl_default.toml" --out "$OUT/ncl_default.h5" --quiet >>"$log" 2>&1
  "$BIN" export "$OUT/ncl_default.h5" --csv "$OUT/ncl_default.csv" >>"$log" 2>&1
  echo "$(sha256sum "$OUT/ncl_default.csv" | cut -c1-64)  ncl_default.csv" >> "$OUT/hashes.txt.part"
fi
study paper.toml tiny paper-tiny
study rate.toml tiny rate-tiny
if [[ $small == 1 ]]; then study paper.toml small paper-small; fi
mv "$OUT/hashes.txt.part" "$OUT/hashes.txt"
echo "$(wc -l < "$OUT/hashes.txt") files hashed: $OUT/hashes.txt"
