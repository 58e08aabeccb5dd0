# Paper Fig. 17: constant-e cross-sections of the ASBS, q/p_e* against
# p/p_e* (data/fig17_dem.tsv, one block per ln(1+e) level; point_type 7
# detected, 6 drifting; a hover label last) with each calibrated model's
# section at the same levels (data/fig17_models.tsv, blocks model-major:
# block m*n_levels + l), one panel per model (one panel of states without
# models). Variables: n_levels, level_titles, n_models, model_titles, x_hi,
# y_lo, y_hi (the axes, from the states).
n_panels = n_models > 0 ? n_models : 1
width = 3.6 * n_panels + 2.2; height = 4.2
load scripts."/common.gp"
dem = data."/fig17_dem.tsv"
models = data."/fig17_models.tsv"
right = 1.0 - 2.1 / width
set multiplot layout 1,n_panels margins 0.55/width,right,0.13,0.9 spacing 0.45/width
set xlabel label_p_norm
set ylabel label_q_norm
set xrange [0:x_hi]
set yrange [y_lo:y_hi]
do for [m=0:n_panels-1] {
  set title (n_models > 0 ? word(model_titles, m+1) : "DEM asymptotic states") font ",9"
  if (m == n_panels-1) {
    set key at screen right + 0.2/width, 0.88 left top Left reverse samplen 2 spacing 1.1 font ",8" maxrows 30
  } else {
    unset key
  }
  # Macros expand before a loop runs: the panel's plot is a string, evaluated.
  models_clause = n_models > 0 ? sprintf('for [l=0:n_levels-1] models index (%d*n_levels+l) using "p_over_pe":"q_over_pe" with lines lt (l+1) lw 1.2, ', m) : ''
  eval 'plot '.models_clause. \
       'for [l=0:n_levels-1] dem index l using "p_over_pe":"q_over_pe":"point_type" with points pt variable ps 0.8 lt (l+1), '. \
       'for [l=0:n_levels-1] dem index l using "p_over_pe":"q_over_pe":"label" with labels hypertext point pt 7 ps 0.8 lc rgb "#ff000000", '. \
       'for [l=0:n_levels-1] dem index l using "p_over_pe":"q_over_pe":(sprintf("%.0f", column("psi_epsilon_deg"))) with labels offset char 0.8,0.45 font ",6" tc lt (l+1), '. \
       'for [l=1:n_levels] keyentry with points pt 7 ps 0.8 lt l title word(level_titles, l), '. \
       'keyentry with points pt 7 lc rgb "black" title "detected", '. \
       'keyentry with points pt 6 lc rgb "black" title "still drifting", '. \
       (n_models > 0 ? 'keyentry with lines lc rgb "black" title "the panel''s model"' : 'NaN notitle')
  unset ylabel
}
unset multiplot
