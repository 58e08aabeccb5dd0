# Paper Fig. 22: the inertial number against p for the smallest and largest
# diameters (data/fig22_inertial.tsv), with I = 1e-2 and 1e-3.
# Variables: n_curves, i_lo (the lower end of the I axis).
width = 7.5; height = 4.5
panels_right = 0.64
load scripts."/common.gp"
set lmargin at screen 0.11
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.92 left top Left reverse samplen 2 spacing 1.1 font ",8"
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set xlabel label_p
set ylabel "I (–)"
# Both reference lines inside the axis, whatever the data's range (i_lo).
set yrange [i_lo:*]
plot for [i=0:n_curves-1] data."/fig22_inertial.tsv" index i using "p_kpa":"inertial_number" \
       with lines lt (i+1) title columnheader(3), \
     1e-2 with lines dt 2 lc rgb "black" title "I = 10^{-2} (quasi-static)", \
     1e-3 with lines dt 3 lc rgb "black" title "I = 10^{-3}"
