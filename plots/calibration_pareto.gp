# The Pareto front of a calibration: the RMS weighted residual of one group of
# data against the other's (the asymptotic states against the whole paths
# where the calibration has paths, else the compression side — NCL,
# compression and ASBS states — against the critical and extension states;
# the groups' names from pareto.csv label the axes) over a weighted-sum
# sweep (pareto.csv), with the ordinary fit (equal weights) and the chosen
# compromise (the knee) marked. Fits that coincide (the same costs within
# the merging tolerance over a range of weights) are one point labelled with
# its weight range; labels are drawn where pareto.csv's `labelled` says (kept
# apart), alternately above and below the front. Data written by `granasym
# calibrate` and `granasym study calibrate` into the plot-data folder.
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
stats f using (column("distinct")) nooutput
distinct = int(STATS_max) + 1
plot f using 4:5 with linespoints pt 7 ps 1 lw 1.5 lc rgb "#1f77b4" title sprintf("front (%d distinct points)", distinct), \
     f using 4:5:(column("labelled") == 1 && int(column("distinct")) % 2 == 0 ? strcol("label") : "") with labels left rotate by 30 offset 0.6,0.6 font ",8" notitle, \
     f using 4:5:(column("labelled") == 1 && int(column("distinct")) % 2 == 1 ? strcol("label") : "") with labels right rotate by 30 offset -0.6,-0.6 font ",8" notitle, \
     f using (column("ordinary") == 1 ? column(4) : NaN):5 with points pt 5 ps 2 lc rgb "black" title "ordinary fit (w = 0.5)", \
     f using (column("compromise") == 1 ? column(4) : NaN):5 with points pt 3 ps 3 lw 2 lc rgb "#d62728" title "compromise (knee)"
