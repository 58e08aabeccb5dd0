#!/usr/bin/env bash
# Whole-run comparison of granasym with LAMMPS (gran/hooke/history) and Yade
# (FrictMat + Cundall-Strack) on the same periodic packing under the same
# loading: proportional straining at psi_epsilon = PSI (default 0: isotropic
# compression; 90: isochoric axial compression), velocity gradient
# L = diag(-eps_a, -eps_r, -eps_r) with |D| = 167 1/s (SPEC section 2, axis 1
# = x the axial one), dt = 1.2e-7 s, K steps.  Not part of CI.  See README.md
# in this directory.
#
# usage: compare.sh --packing FILE [--steps K] [--threads T] [--psi PSI]
#                   [--granasym PATH] [--out DIR] [--repeat R]
#                   [--skin-frac F] [--lammps-gamma G] [--lammps-mpi]
#                   [--skip-granasym] [--skip-lammps] [--skip-yade] [--no-install]
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

PACKING=""
STEPS=2000
THREADS=1
GRANASYM="build/app/granasym"
OUT="external_compare_out"
REPEAT=1
SKIN_FRAC=0.1
LMP_GAMMA=0.0
LMP_MPI=0
SKIP_G=0
SKIP_L=0
SKIP_Y=0
INSTALL=1
STRETCH=167.0
PSI=0

usage() { sed -n '2,12p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; }

while [[ $# -gt 0 ]]; do
  case "$1" in
    --packing) PACKING="$2"; shift 2 ;;
    --steps) STEPS="$2"; shift 2 ;;
    --threads) THREADS="$2"; shift 2 ;;
    --psi) PSI="$2"; shift 2 ;;
    --granasym) GRANASYM="$2"; shift 2 ;;
    --out) OUT="$2"; shift 2 ;;
    --repeat) REPEAT="$2"; shift 2 ;;
    --skin-frac) SKIN_FRAC="$2"; shift 2 ;;
    --lammps-gamma) LMP_GAMMA="$2"; shift 2 ;;
    --lammps-mpi) LMP_MPI=1; shift ;;
    --skip-granasym) SKIP_G=1; shift ;;
    --skip-lammps) SKIP_L=1; shift ;;
    --skip-yade) SKIP_Y=1; shift ;;
    --no-install) INSTALL=0; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "compare.sh: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
  esac
done

[[ -n "$PACKING" ]] || { echo "compare.sh: --packing FILE is required" >&2; exit 2; }
[[ -f "$PACKING" ]] || { echo "compare.sh: packing '$PACKING' not found" >&2; exit 2; }
[[ "$STEPS" =~ ^[0-9]+$ && "$STEPS" -gt 0 ]] || { echo "--steps must be a positive integer" >&2; exit 2; }
[[ "$THREADS" =~ ^[0-9]+$ && "$THREADS" -gt 0 ]] || { echo "--threads must be a positive integer" >&2; exit 2; }
[[ "$REPEAT" =~ ^[0-9]+$ && "$REPEAT" -gt 0 ]] || { echo "--repeat must be a positive integer" >&2; exit 2; }
[[ "$PSI" =~ ^-?[0-9]+([.][0-9]+)?$ ]] && awk -v p="$PSI" 'BEGIN { exit !(p >= 0 && p <= 180) }' ||
  { echo "--psi must be a number of degrees in [0, 180], got '$PSI'" >&2; exit 2; }

mkdir -p "$OUT"
OUT="$(cd "$OUT" && pwd)"
PACKING="$(cd "$(dirname "$PACKING")" && pwd)/$(basename "$PACKING")"
if [[ "$GRANASYM" != /* && -e "$GRANASYM" ]]; then
  GRANASYM="$(cd "$(dirname "$GRANASYM")" && pwd)/$(basename "$GRANASYM")"
fi

# Velocity gradient components (tension positive) of psi_epsilon = PSI:
# eps_a = |D| (cos/sqrt3 + sin sqrt(2/3)), eps_r = |D| (cos/sqrt3 - sin/sqrt6).
RATE_A="$(python3 -c "import math; p = math.radians($PSI); print(repr(-$STRETCH * (math.cos(p) / math.sqrt(3) + math.sin(p) * math.sqrt(2 / 3))))")"
RATE_R="$(python3 -c "import math; p = math.radians($PSI); print(repr(-$STRETCH * (math.cos(p) / math.sqrt(3) - math.sin(p) / math.sqrt(6))))")"
NPART="$(head -n1 "$PACKING" | awk '{print $1}')"
RESULTS="$OUT/results.tsv"
NOTES="$OUT/notes.txt"
: > "$RESULTS"
: > "$NOTES"
note() { echo "note: $*"; echo "$*" >> "$NOTES"; }

now() { date +%s.%N; }

# ---------------------------------------------------------------- packages
find_lmp() {
  local b
  for b in lmp lmp_serial lmp_mpi; do
    if command -v "$b" > /dev/null 2>&1; then echo "$b"; return 0; fi
  done
  return 1
}
need_pkgs=()
if [[ $SKIP_L -eq 0 ]] && ! find_lmp > /dev/null; then need_pkgs+=(lammps); fi
if [[ $SKIP_Y -eq 0 ]] && ! command -v yade > /dev/null 2>&1; then need_pkgs+=(yade); fi
if [[ ${#need_pkgs[@]} -gt 0 ]]; then
  if [[ $INSTALL -eq 1 ]]; then
    SUDO=""
    if [[ $EUID -ne 0 ]] && command -v sudo > /dev/null 2>&1; then SUDO="sudo"; fi
    echo "installing ${need_pkgs[*]} (Debian packages) ..."
    if ! DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y "${need_pkgs[@]}"; then
      $SUDO apt-get update
      DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y "${need_pkgs[@]}" \
        || echo "compare.sh: could not install ${need_pkgs[*]}" >&2
    fi
  else
    echo "compare.sh: missing ${need_pkgs[*]} and --no-install given" >&2
  fi
fi

median() { python3 -c "import statistics,sys; print(statistics.median(float(v) for v in sys.argv[1:]))" "$@"; }

# Each code is set up once, then run R times in rounds (granasym, LAMMPS,
# Yade, granasym, ...), so that a change of the host's speed during the
# script reaches every code alike. The table gives the median of each code's
# loop times and, per code, the median over the rounds of its loop time over
# granasym's in the same round (the paired ratio).
WALLS="$OUT/walls.tsv"
: > "$WALLS"
G_ON=0; L_ON=0; Y_ON=0
G_WALLS=(); L_WALLS=(); Y_WALLS=()
wall_row() { printf '%s\t%s\t%s\n' "$1" "$2" "$3" >> "$WALLS"; }

# ---------------------------------------------------------------- granasym
G_DIR="$OUT/granasym"
setup_granasym() {
  mkdir -p "$G_DIR"
  if [[ $SKIP_G -eq 1 ]]; then note "granasym skipped: --skip-granasym"; return 0; fi
  if [[ ! -x "$GRANASYM" ]] && ! command -v "$GRANASYM" > /dev/null 2>&1; then
    note "granasym skipped: binary '$GRANASYM' not found (pass --granasym PATH)"
    return 0
  fi
  cp "$PACKING" "$G_DIR/packing.txt"
  # A row every quarter of the run, as LAMMPS's thermo output (steps/4);
  # interval_strain is set out of reach so that only these rows are measured.
  local interval=$(( STEPS / 4 > 0 ? STEPS / 4 : 1 ))
  cat > "$G_DIR/scene.toml" <<EOF
# generated by bench/external/compare.sh
[sample]
packing = "packing.txt"

[material]
youngs_modulus_mpa = 500.0
stiffness_ratio = 0.3
friction_angle_rad = 0.5
density_kg_m3 = 2650.0
local_damping = 0.5

[numerics]
time_step_s = 1.2e-7

[output]
interval_steps = $interval
interval_strain = 1.0e9

[[stage]]
name = "compress"
type = "strain_path"
psi_epsilon_deg = $PSI
stretching_rate = $STRETCH

[stage.stop]
steps = $STEPS
EOF
  G_ON=1
}
round_granasym() {
  local i="$1" t0 t1 w
  rm -f "$G_DIR/run.h5" "$G_DIR/run.csv"
  t0="$(now)"
  if ! (cd "$G_DIR" && "$GRANASYM" dem run scene.toml --out run.h5 --threads "$THREADS") \
       > "$G_DIR/stdout.txt" 2> "$G_DIR/stderr.txt"; then
    note "granasym skipped: 'granasym dem run' failed (see $G_DIR/stderr.txt): $(tail -n 2 "$G_DIR/stderr.txt" | tr '\n' ' ')"
    G_ON=0; G_WALLS=()
    return 0
  fi
  t1="$(now)"
  # loop wall time: the run file's /summary loop_wall_s, read by granasym itself
  w="$("$GRANASYM" export "$G_DIR/run.h5" --info 2> /dev/null \
       | sed -n 's/^loop_wall_s: *\([-0-9.eE+]*\)$/\1/p' | head -n1 || true)"
  if [[ -z "$w" ]]; then
    w="$(python3 -c "print($t1 - $t0)")"
    [[ $i -eq 1 ]] && note "granasym: 'granasym export --info' gave no loop_wall_s; using whole-command wall time incl. setup"
  fi
  G_WALLS+=("$w"); wall_row granasym "$i" "$w"
}
finish_granasym() {
  [[ $G_ON -eq 1 ]] || return 0
  if ! (cd "$G_DIR" && "$GRANASYM" export run.h5 --csv run.csv) > "$G_DIR/export.txt" 2>&1; then
    note "granasym: 'granasym export' failed (see $G_DIR/export.txt); p and e unknown"
    printf 'granasym\t%s\t%s\t%s\t%s\tnan\tnan\n' "$THREADS" "$NPART" "$STEPS" "$(median "${G_WALLS[@]}")" >> "$RESULTS"
    return 0
  fi
  local pe
  pe="$(python3 - "$G_DIR/run.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
last = max(rows, key=lambda r: float(r["step"]))
print(last["p_kpa"], last["e"])
PY
)" || { note "granasym: could not read step/p_kpa/e from run.csv"; pe="nan nan"; }
  local gp ge
  read -r gp ge <<< "$pe"
  printf 'granasym\t%s\t%s\t%s\t%s\t%s\t%s\n' "$THREADS" "$NPART" "$STEPS" \
    "$(median "${G_WALLS[@]}")" "${gp:-nan}" "${ge:-nan}" >> "$RESULTS"
}

# ---------------------------------------------------------------- LAMMPS
L_DIR="$OUT/lammps"
L_CMD=()
L_TLABEL="$THREADS"
setup_lammps() {
  mkdir -p "$L_DIR"
  if [[ $SKIP_L -eq 1 ]]; then note "LAMMPS skipped: --skip-lammps"; return 0; fi
  local lmp
  if ! lmp="$(find_lmp)"; then note "LAMMPS skipped: no lmp / lmp_serial / lmp_mpi binary"; return 0; fi
  python3 "$HERE/lammps_input.py" --packing "$PACKING" --dir "$L_DIR" --steps "$STEPS" \
    --rate "$RATE_A" --rate-yz "$RATE_R" --gamma "$LMP_GAMMA" --skin-frac "$SKIN_FRAC" > /dev/null
  while IFS= read -r line; do note "$line"; done < "$L_DIR/notes.txt"
  L_CMD=("$lmp")
  if [[ $THREADS -gt 1 ]]; then
    if "$lmp" -h 2> /dev/null | sed -n '/Installed packages/,/^List of/p' | grep -qw OPENMP; then
      L_CMD=("$lmp" -sf omp -pk omp "$THREADS")
    elif [[ $LMP_MPI -eq 1 ]] && command -v mpirun > /dev/null 2>&1; then
      L_CMD=(mpirun --allow-run-as-root --oversubscribe -np "$THREADS" "$lmp")
      L_TLABEL="${THREADS}mpi"
      note "LAMMPS: no OPENMP package; ran $THREADS MPI ranks instead of threads"
    else
      L_TLABEL=1
      note "LAMMPS: this build has no OPENMP package; ran serial (1 thread). --lammps-mpi runs MPI ranks instead"
    fi
  fi
  L_ON=1
}
round_lammps() {
  local i="$1" w
  if ! (cd "$L_DIR" && OMP_NUM_THREADS="$THREADS" "${L_CMD[@]}" -in in.lmp -log log.lammps) \
       > "$L_DIR/stdout.txt" 2>&1; then
    note "LAMMPS failed (see $L_DIR/stdout.txt): $(grep -m1 ERROR "$L_DIR/stdout.txt" || tail -n1 "$L_DIR/stdout.txt")"
    L_ON=0; L_WALLS=()
    return 0
  fi
  w="$(sed -n 's/^Loop time of \([-0-9.eE+]*\) on .*/\1/p' "$L_DIR/stdout.txt" | tail -n1)"
  L_WALLS+=("$w"); wall_row lammps "$i" "$w"
}
finish_lammps() {
  [[ $L_ON -eq 1 ]] || return 0
  local res p e
  res="$(grep '^RESULT code=lammps' "$L_DIR/stdout.txt" | tail -n1)"
  p="$(sed -n 's/.* p_kpa=\([^ ]*\).*/\1/p' <<< "$res")"
  e="$(sed -n 's/.* e=\([^ ]*\).*/\1/p' <<< "$res")"
  printf 'lammps\t%s\t%s\t%s\t%s\t%s\t%s\n' "$L_TLABEL" "$NPART" "$STEPS" \
    "$(median "${L_WALLS[@]}")" "${p:-nan}" "${e:-nan}" >> "$RESULTS"
}

# ---------------------------------------------------------------- Yade
Y_DIR="$OUT/yade"
Y_RES=""
setup_yade() {
  mkdir -p "$Y_DIR"
  if [[ $SKIP_Y -eq 1 ]]; then note "Yade skipped: --skip-yade"; return 0; fi
  if ! command -v yade > /dev/null 2>&1; then note "Yade skipped: no yade binary"; return 0; fi
  Y_ON=1
}
round_yade() {
  local i="$1" w
  # -n: no GUI, -x: exit when the script ends, -j: OpenMP threads
  if ! (cd "$Y_DIR" && yade -j "$THREADS" -n -x "$HERE/yade_run.py" "$PACKING" "$STEPS" "$RATE_A" "$SKIN_FRAC" 0.5 "$RATE_R") \
       > "$Y_DIR/stdout.txt" 2>&1; then
    note "Yade failed (see $Y_DIR/stdout.txt): $(tail -n1 "$Y_DIR/stdout.txt")"
    Y_ON=0; Y_WALLS=()
    return 0
  fi
  Y_RES="$(grep '^RESULT code=yade' "$Y_DIR/stdout.txt" | tail -n1)"
  if [[ -z "$Y_RES" ]]; then
    note "Yade: no RESULT line (see $Y_DIR/stdout.txt)"
    Y_ON=0; Y_WALLS=()
    return 0
  fi
  w="$(sed -n 's/.* wall_s=\([^ ]*\).*/\1/p' <<< "$Y_RES")"
  Y_WALLS+=("$w"); wall_row yade "$i" "$w"
}
finish_yade() {
  [[ $Y_ON -eq 1 ]] || return 0
  local p e
  p="$(sed -n 's/.* p_kpa=\([^ ]*\).*/\1/p' <<< "$Y_RES")"
  e="$(sed -n 's/.* e=\([^ ]*\).*/\1/p' <<< "$Y_RES")"
  printf 'yade\t%s\t%s\t%s\t%s\t%s\t%s\n' "$THREADS" "$NPART" "$STEPS" \
    "$(median "${Y_WALLS[@]}")" "${p:-nan}" "${e:-nan}" >> "$RESULTS"
}

echo "packing: $PACKING (N = $NPART), steps = $STEPS, threads = $THREADS, repeat = $REPEAT"
echo "loading: psi_epsilon = $PSI deg, L = diag($RATE_A, $RATE_R, $RATE_R) 1/s, dt = 1.2e-7 s"
setup_granasym
setup_lammps
setup_yade
for ((round = 1; round <= REPEAT; round++)); do
  if [[ $G_ON -eq 1 ]]; then round_granasym "$round"; fi
  if [[ $L_ON -eq 1 ]]; then round_lammps "$round"; fi
  if [[ $Y_ON -eq 1 ]]; then round_yade "$round"; fi
done
finish_granasym
finish_lammps
finish_yade

# ---------------------------------------------------------------- table
python3 - "$RESULTS" "$OUT/comparison.csv" "$REPEAT" "$WALLS" <<'PY'
import csv, math, statistics, sys
rows = []
for line in open(sys.argv[1]):
    c = line.rstrip("\n").split("\t")
    if len(c) < 7:
        continue
    code, thr, n, steps, wall, p, e = c[:7]
    n, steps, wall, p, e = int(n), int(steps), float(wall), float(p), float(e)
    rows.append(dict(code=code, threads=thr, N=n, steps=steps, wall_s=wall,
                     us_per_particle_step=wall / (n * steps) * 1e6, p_kpa=p, e=e))
# Loop times per round: {code: {round: wall}}.
walls = {}
for line in open(sys.argv[4]):
    c = line.rstrip("\n").split("\t")
    if len(c) == 3:
        walls.setdefault(c[0], {})[c[1]] = float(c[2])
ref = next((r for r in rows if r["code"] == "granasym"), None)
for r in rows:
    if ref is not None:
        r["ratio_to_granasym"] = r["us_per_particle_step"] / ref["us_per_particle_step"]
        r["dp_kpa"] = r["p_kpa"] - ref["p_kpa"]
        r["de"] = r["e"] - ref["e"]
        # Same particles and steps, so the ratio of loop times is the ratio
        # of times per particle-step.
        mine, theirs = walls.get(r["code"], {}), walls.get("granasym", {})
        pairs = [mine[k] / theirs[k] for k in mine if k in theirs and theirs[k] > 0]
        r["paired_ratio"] = statistics.median(pairs) if pairs else float("nan")
    else:
        r["ratio_to_granasym"] = r["dp_kpa"] = r["de"] = r["paired_ratio"] = float("nan")
cols = ["code", "threads", "N", "steps", "wall_s", "us_per_particle_step",
        "ratio_to_granasym", "paired_ratio", "p_kpa", "e", "dp_kpa", "de"]
heads = ["code", "thr", "N", "steps", "wall [s]", "us/(part*step)", "ratio/granasym",
         "paired", "p [kPa]", "e", "dp [kPa]", "de"]
def fmt(k, v):
    if isinstance(v, str):
        return v
    if isinstance(v, int):
        return str(v)
    if math.isnan(v):
        return "n/a"
    return {"wall_s": "%.4f", "us_per_particle_step": "%.4f", "ratio_to_granasym": "%.2f",
            "paired_ratio": "%.2f",
            "p_kpa": "%.4g", "e": "%.6f", "dp_kpa": "%+.4g", "de": "%+.2e"}[k] % v
table = [heads] + [[fmt(k, r[k]) for k in cols] for r in rows]
w = [max(len(t[i]) for t in table) for i in range(len(heads))]
print()
print("wall time: time-stepping loop only (median of %s run(s), the codes in rounds); ratio = us/(part*step) of "
      "the code / granasym's; paired = median over the rounds of the code's loop time / granasym's in the same round"
      % sys.argv[3])
for t in table:
    print("  ".join(s.rjust(w[i]) for i, s in enumerate(t)))
lmp = next((r for r in rows if r["code"] == "lammps"), None)
yd = next((r for r in rows if r["code"] == "yade"), None)
if lmp and yd:
    print("Yade / LAMMPS time per particle-step: %.2f" % (yd["us_per_particle_step"] / lmp["us_per_particle_step"]))
if ref is not None:
    # The targets of the issues that set them: issue 2 (granasym faster than
    # LAMMPS, 20x faster than Yade) and issue 11 (2x LAMMPS, 40x Yade).
    targets = [("LAMMPS", lmp, 1.0, "faster than LAMMPS per particle-step (issue 2)"),
               ("LAMMPS", lmp, 2.0, ">= 2x faster than LAMMPS (issue 11)"),
               ("Yade", yd, 20.0, ">= 20x faster than Yade (issue 2)"),
               ("Yade", yd, 40.0, ">= 40x faster than Yade (issue 11)")]
    for name, row, bound, text in targets:
        if not row:
            continue
        ratio = row["ratio_to_granasym"]
        met = ratio > bound if bound == 1.0 else ratio >= bound
        print("target: granasym %s: %s (%s / granasym = %.2f, paired %.2f)"
              % (text, "met" if met else "NOT met", name, ratio, row["paired_ratio"]))
with open(sys.argv[2], "w", newline="") as f:
    wr = csv.writer(f)
    wr.writerow(cols)
    for r in rows:
        wr.writerow([r[k] for k in cols])
print("csv: %s" % sys.argv[2])
PY
if [[ -s "$NOTES" ]]; then
  echo
  echo "notes:"
  sed 's/^/  - /' "$NOTES"
fi
