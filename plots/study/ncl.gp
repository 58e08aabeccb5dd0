# Paper Fig. 9: ln(1+e) against p along the isotropic NCL and the
# unload/reload cycles (data/fig09_paths.tsv; the last block, when has_fit,
# is the fitted NCL). Variables: n_paths, has_fit.
width = 7.5; height = 4.5
panels_right = 0.62
load scripts."/common.gp"
set lmargin at screen 0.1
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.92 left top Left reverse samplen 2 spacing 1.1 font ",8"
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_lnv
file = data."/fig09_paths.tsv"
# The fitted NCL is an optional layer, a macro (gnuplot reads a file even for
# an empty loop).
fit_layer = has_fit > 0 ? ', for [i=n_paths:n_paths+has_fit-1] file index i using "p_kpa":"ln_1_plus_e" with lines dt 2 lc rgb "black" title columnheader(3)' : ''
plot for [i=0:n_paths-1] file index i using "p_kpa":"ln_1_plus_e" with lines lt (i+1) \
       title columnheader(3) @fit_layer
