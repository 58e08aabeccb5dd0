# ASBS cross-sections: q/p_e* against p/p_e* (p_e* of the fitted NCL at each
# state's void ratio), data (states.csv) against the model's asymptotic state
# boundary surface (model_curve.csv).
# Usage: gnuplot -e "dir='CONFIG_plots'" plots/calibration_asbs.gp   (writes dir/asbs.png)
if (!exists("dir")) dir = "."
set terminal pngcairo size 800,600 font ",11"
set output dir."/asbs.png"
set datafile separator ","
set xlabel "p/p_e^*"
set ylabel "q/p_e^*"
set key right top
set grid
set xrange [0:*]
plot dir."/model_curve.csv" using "p_over_pe":"q_over_pe" with lines lw 2 lc rgb "black" title "model ASBS", \
     dir."/states.csv" using (column("kind")==5 ? 1/0 : column("p_over_pe")):"q_over_pe" \
       with points pt 7 lc rgb "#1f77b4" title "data"
