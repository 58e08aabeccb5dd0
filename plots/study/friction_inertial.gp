# Paper Fig. 21 (the study's counterpart): the critical-state stress ratio
# q/p against the inertial number for the smallest and largest diameters
# (data/fig21_friction_inertial.tsv, blocks: I(d_min), I(d_max)), with the
# quasi-static limit I = 1e-2.
width = 7.5; height = 4.5
panels_right = 0.70
load scripts."/common.gp"
set lmargin at screen 0.11
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.92 left top Left reverse samplen 2 spacing 1.1 font ",8"
set logscale x
set format x "10^{%T}"
set xlabel "I (–)"
set ylabel "q/p (–)"
set arrow from 1e-2, graph 0 to 1e-2, graph 1 nohead dt 2 lc rgb "black"
plot for [i=0:1] data."/fig21_friction_inertial.tsv" index i using "inertial_number":"q_over_p" \
       with points pt 7 ps 0.7 lt (i+1) title columnheader(3), \
     NaN with lines dt 2 lc rgb "black" title "I = 10^{-2} (quasi-static)"
