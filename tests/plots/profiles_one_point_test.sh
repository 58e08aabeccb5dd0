#!/bin/bash
# plots/calibration_profiles.gp draws a profile of a single point (a
# parameter pinned between two others, whose first profile step already
# fails: the sand model's e_c0 between e_d0 and e_i0) with a range about it,
# beside an ordinary profile, instead of failing on an empty x range.
# Usage: profiles_one_point_test.sh SOURCE_DIR WORK_DIR
set -u
source_dir=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
cat > "$work/profile_parameters.csv" <<'CSV'
parameter,log_scale,optimum,threshold,flat,low,high,low_crossed,high_crossed
phi_c_deg,0,19.5,4.96,0,18.0,21.1,1,1
e_c0,0,0.7144,4.96,1,0.7144,0.7144,0,0
h_s_kpa,1,8.7e8,4.96,1,8.7e7,1e9,0,0
CSV
cat > "$work/profiles.csv" <<'CSV'
parameter,value,cost,statistic,threshold,converged,log_scale,optimum,ci95_low,ci95_high,flat
phi_c_deg,17.0,100,10.0,4.96,1,0,19.5,18.0,21.1,0
phi_c_deg,19.5,90,0.0,4.96,1,0,19.5,18.0,21.1,0
phi_c_deg,22.0,100,10.0,4.96,1,0,19.5,18.0,21.1,0
e_c0,0.7144,90,0.0,4.96,1,0,0.7144,0.7144,0.7144,1
h_s_kpa,8.7e8,90,0.0,4.96,1,1,8.7e8,8.7e7,1e9,1
CSV
gnuplot -e "dir='$work'" "$source_dir/plots/calibration_profiles.gp" || { echo "FAIL: gnuplot"; exit 1; }
[ -s "$work/profiles.png" ] || { echo "FAIL: no profiles.png"; exit 1; }
echo "PASS: a one-point profile is drawn"
