# Asymptotic stress direction psi_sigma against the stretching direction
# psi_epsilon: calibration data (states.csv) and the fitted model's asymptote
# curve (model_curve.csv).
# Usage: gnuplot -e "dir='CONFIG_plots'" plots/calibration_psi.gp   (writes dir/psi.png)
if (!exists("dir")) dir = "."
set terminal pngcairo size 800,600 font ",11"
set output dir."/psi.png"
set datafile separator ","
set xlabel "psi_{/Symbol e} (deg)"
set ylabel "psi_{/Symbol s} (deg)"
set key left top
set grid
plot dir."/model_curve.csv" using "psi_epsilon_deg":"psi_sigma_deg" with lines lw 2 lc rgb "black" title "model asymptotes", \
     dir."/states.csv" using (column("kind")==4 || column("kind")==5 ? 1/0 : column("psi_epsilon_deg")):"psi_sigma_deg" \
       with points pt 7 lc rgb "#d62728" title "data"
