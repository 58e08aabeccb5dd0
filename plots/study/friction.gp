# Paper Fig. 20: frictionless contacts against phi = 0.5 rad: (a) the NCLs
# (data/<stem>_ncl.tsv), (b) q-p paths of the psi_epsilon = 90 deg tests
# (data/<stem>_paths.tsv). Colours: the study's sample 1, the other 2
# (ncl_colours, path_colours); dash types: one per start (path_dashes,
# start_titles); sample_titles. Variables also: stem, n_ncl, n_paths.
width = 10.0; height = 4.2
panels_right = 0.72
load scripts."/common.gp"
ncl = data."/".stem."_ncl.tsv"
paths = data."/".stem."_paths.tsv"
ncl_colour(i) = int(word(ncl_colours, i+1))
path_colour(i) = int(word(path_colours, i+1))
path_dash(i) = int(word(path_dashes, i+1))
set multiplot layout 1,2 margins 0.07,panels_right,0.14,0.92 spacing 0.09,0.1
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_lnv
set title "(a)"
plot for [i=0:n_ncl-1] ncl index i using "p_kpa":"ln_1_plus_e" with lines lt ncl_colour(i)
set key at screen panels_right + 0.015, 0.92 left top Left reverse samplen 3 spacing 1.1 font ",8"
set title "(b)"
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_q
plot for [i=0:n_paths-1] paths index i using "p_kpa":"q_kpa" with lines lt path_colour(i) dt path_dash(i), \
     for [i=1:2] keyentry with lines lt i lw 1.3 title word(sample_titles, i), \
     for [j=1:words(start_titles)] keyentry with lines lc rgb "#333333" dt j title word(start_titles, j)
unset multiplot
