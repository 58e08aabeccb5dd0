# Paper Fig. 17: constant-e cross-sections of the ASBS, q/p_e* against
# p/p_e* (data/fig17_dem.tsv, one block per ln(1+e) level; point_type 7
# detected, 6 drifting; labels: psi_epsilon) with each calibrated model's
# section at the same levels (data/fig17_models.tsv, blocks model-major:
# block m*n_levels + l). Variables: n_levels, level_titles (quoted words), n_models.
width = 10.5; height = 5.5
panels_right = 0.55
load scripts."/common.gp"
dem = data."/fig17_dem.tsv"
models = data."/fig17_models.tsv"
model_dt(b) = b/n_levels + 2
# Optional layers are macros (gnuplot reads a file even for an empty loop).
models_clause = n_models > 0 ? 'for [b=0:n_levels*n_models-1] models index b using "p_over_pe":"q_over_pe" with lines lt (b%n_levels+1) dt model_dt(b) title columnheader(3),' : ''
set lmargin at screen 0.09
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.93 left top Left reverse samplen 3 spacing 1.1 font ",8"
set xlabel label_p_norm
set ylabel label_q_norm
set xrange [0:*]
set yrange [*:*]
plot for [l=0:n_levels-1] dem index l using "p_over_pe":"q_over_pe":"point_type" \
       with points pt variable ps 0.9 lt (l+1), \
     for [l=0:n_levels-1] keyentry with points pt 7 ps 0.9 lt (l+1) title word(level_titles, l+1), \
     for [l=0:n_levels-1] dem index l using "p_over_pe":"q_over_pe":(sprintf("%.0f", column("psi_epsilon_deg"))) \
       with labels offset char 0.9,0.5 font ",7" tc lt (l+1), \
     @models_clause keyentry with points pt 7 lc rgb "black" title "detected", \
     keyentry with points pt 6 lc rgb "black" title "still drifting"
