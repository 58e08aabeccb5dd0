# Fig. 21 (the study's counterpart): M = q/p of the critical states against
# the inertial number (data/fig21_friction_inertial.tsv: one block per kind;
# each state at sqrt(I(d_min) I(d_max)) with a bar from I(d_min) to
# I(d_max), a hover label last). Variables: n_blocks, block_titles.
width = 7.5; height = 4.5
panels_right = 0.66
load scripts."/common.gp"
file = data."/fig21_friction_inertial.tsv"
set lmargin at screen 0.11
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.92 left top Left reverse samplen 2 spacing 1.1 font ",8"
set logscale x
set format x "10^{%T}"
set xlabel "I (–)"
set ylabel "q/p (–)"
set arrow from 1e-2, graph 0 to 1e-2, graph 1 nohead dt 2 lc rgb "black"
set arrow from 1e-3, graph 0 to 1e-3, graph 1 nohead dt 3 lc rgb "black"
plot for [i=0:n_blocks-1] file index i using "inertial_number":"q_over_p":"i_dmin":"i_dmax" \
       with xerrorbars pt 7 ps 0.6 lt (i+1) notitle, \
     for [i=0:n_blocks-1] file index i using "inertial_number":"q_over_p":"label" \
       with labels hypertext point pt 7 ps 0.6 lc rgb "#ff000000" notitle, \
     for [i=1:n_blocks] keyentry with points pt 7 ps 0.6 lt i title word(block_titles, i), \
     keyentry with lines dt 2 lc rgb "black" title "I = 10^{-2} (quasi-static)", \
     keyentry with lines dt 3 lc rgb "black" title "I = 10^{-3}"
