# The Pareto front of a calibration: the RMS weighted residual of one group of
# data against the other's (the asymptotic states against the whole paths
# where the calibration has paths, else the compression side — NCL,
# compression and ASBS states — against the critical and extension states;
# the groups' names from pareto.csv label the axes) over a weighted-sum
# sweep (pareto.csv), with the ordinary fit (equal weights) and the chosen
# compromise (the knee) marked. Data written by `granasym calibrate` and
# `granasym study calibrate` into the plot-data folder.
# Usage: gnuplot -e "dir='CONFIG_plots'" plots/calibration_pareto.gp   (writes dir/pareto.png)
if (!exists("dir")) dir = "."
set datafile separator ","
f = dir."/pareto.csv"
set datafile columnheaders
stats f every ::0::0 using (group0 = strcol("group_0"), group1 = strcol("group_1"), 0) nooutput
set terminal pngcairo size 800,620 font ",11"
set output dir."/pareto.png"
set title "Pareto front: weighted-sum sweep (w weights ".group0.")" noenhanced
set xlabel "RMS weighted residual, ".group0 noenhanced
set ylabel "RMS weighted residual, ".group1 noenhanced
set grid
set offsets 0, graph 0.1, graph 0.1, 0
set key top right box opaque
plot f using 4:5 with linespoints pt 7 ps 1 lw 1.5 lc rgb "#1f77b4" title "front (w from 0.001 to 0.999)", \
     f using 4:5:(int(column(0)) % 2 == 0 || column("ordinary") == 1 ? sprintf("w = %.3g", column(1)) : "") with labels left rotate by 35 offset 0.5,0.5 font ",8" notitle, \
     f using (column("ordinary") == 1 ? column(4) : NaN):5 with points pt 5 ps 2 lc rgb "black" title "ordinary fit (w = 0.5)", \
     f using (column("compromise") == 1 ? column(4) : NaN):5 with points pt 3 ps 3 lw 2 lc rgb "#d62728" title "compromise (knee)"
