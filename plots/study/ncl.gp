# Paper Fig. 9: the isotropic NCL (psi_epsilon = 0 deg) and the
# unload/reload cycles (data/fig09_paths.tsv; the last block, when has_fit,
# is the fitted NCL line): (a) the whole path, (b) the cycles' range
# enlarged (when has_cycles). Variables: n_paths, has_fit, has_cycles and the
# cycles' range cycle_p_lo, cycle_p_hi, cycle_v_lo, cycle_v_hi.
width = has_cycles ? 10.0 : 7.5; height = 4.5
panels_right = has_cycles ? 0.74 : 0.62
load scripts."/common.gp"
file = data."/fig09_paths.tsv"
fit_layer = has_fit > 0 ? ', for [i=n_paths:n_paths+has_fit-1] file index i using "p_kpa":"ln_1_plus_e" with lines dt 2 lc rgb "black" title columnheader(3)' : ''
set multiplot layout 1,(has_cycles ? 2 : 1) margins 0.08,panels_right,0.13,0.9 spacing 0.08
set key at screen panels_right + 0.015, 0.9 left top Left reverse samplen 2 spacing 1.1 font ",8"
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_lnv
if (has_cycles) { set title "(a)" }
plot for [i=0:n_paths-1] file index i using "p_kpa":"ln_1_plus_e" with lines lt (i+1) \
       title columnheader(3) @fit_layer
if (has_cycles) {
  unset key
  set title "(b)"
  set xrange [cycle_p_lo:cycle_p_hi]
  set yrange [cycle_v_lo:cycle_v_hi]
  set format x "%g"
  plot for [i=0:n_paths-1] file index i using "p_kpa":"ln_1_plus_e" with lines lt (i+1) \
         notitle @fit_layer
}
unset multiplot
