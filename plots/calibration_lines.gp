# NCL, CSL and normal extension lines in ln(1+e)-ln p: calibration data
# (states.csv, coloured by kind) against the fitted model's asymptotic lines
# (model_lines.dat, one block per psi_epsilon). Data written by
# `granasym calibrate` into its plot-data folder.
# Usage: gnuplot -e "dir='CONFIG_plots'" plots/calibration_lines.gp   (writes dir/lines.png)
if (!exists("dir")) dir = "."
set terminal pngcairo size 900,650 font ",11"
set output dir."/lines.png"
set datafile separator ","
set xlabel "ln p (p in kPa)"
set ylabel "ln(1+e)"
set key left bottom box opaque samplen 2
set grid
kinds = "NCL CSL compression extension ASBS unloading"
set style line 1 lc rgb "#1f77b4" pt 7
set style line 2 lc rgb "#d62728" pt 5
set style line 3 lc rgb "#2ca02c" pt 9
set style line 4 lc rgb "#9467bd" pt 11
set style line 5 lc rgb "#8c564b" pt 13
set style line 6 lc rgb "#7f7f7f" pt 6
stats dir."/model_lines.dat" using 1 nooutput
blocks = STATS_blocks
plot for [k=0:5] dir."/states.csv" using (column("kind")==k ? column("ln_p") : 1/0):"ln_1_plus_e" \
       with points ls (k+1) title word(kinds, k+1), \
     for [b=0:blocks-1] dir."/model_lines.dat" index b using 2:3 with lines lc rgb "black" \
       dt 2 notitle, \
     for [b=0:blocks-1] dir."/model_lines.dat" index b using ($1==0 ? $2 : 1/0):3 with lines lw 2 \
       lc rgb "black" title (b==0 ? "model NCL (solid), other psi_{/Symbol e} (dashed)" : "")
