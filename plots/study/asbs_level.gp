# Paper Fig. 18: the ASBS section at one ln(1+e) (data/fig18_dem.tsv) with
# the NC and OC psi_epsilon = 90 deg paths nearest to it (data/fig18_paths.tsv)
# and the calibrated models' sections (data/fig18_models.tsv);
# (a) logarithmic, (b) linear p/p_e*; a hover label on each state. Variables:
# n_paths, n_models, x_lo, x_hi, y_lo, y_hi (the axes, from the DEM's data).
width = 11.0; height = 4.5
panels_right = 0.66
load scripts."/common.gp"
dem = data."/fig18_dem.tsv"
paths = data."/fig18_paths.tsv"
models = data."/fig18_models.tsv"
model_dt(m) = m + 2
# Optional layers are macros (gnuplot reads a file even for an empty loop).
paths_a = n_paths > 0 ? 'for [i=0:n_paths-1] paths index i using "p_over_pe":"q_over_pe" with lines lt (i+1) title columnheader(3),' : ''
paths_b = n_paths > 0 ? 'for [i=0:n_paths-1] paths index i using "p_over_pe":"q_over_pe" with lines lt (i+1),' : ''
models_a = n_models > 0 ? 'for [m=0:n_models-1] models index m using "p_over_pe":"q_over_pe" with lines lc rgb "#555555" dt model_dt(m) title columnheader(3),' : ''
models_b = n_models > 0 ? 'for [m=0:n_models-1] models index m using "p_over_pe":"q_over_pe" with lines lc rgb "#555555" dt model_dt(m),' : ''
set multiplot layout 1,2 margins 0.06,panels_right,0.13,0.92 spacing 0.08,0.1
set key at screen panels_right + 0.015, 0.92 left top Left reverse samplen 3 spacing 1.1 font ",8"
set xlabel label_p_norm
set ylabel label_q_norm
set logscale x
set format x "10^{%T}"
set xrange [x_lo:x_hi]
set yrange [y_lo:y_hi]
set title "(a)"
plot @paths_a @models_a \
     dem index 0 using "p_over_pe":"q_over_pe":(sprintf("%.0f", column("psi_epsilon_deg"))) \
       with labels offset char 0.9,0.5 font ",7", \
     dem index 0 using "p_over_pe":"q_over_pe":"point_type" with points pt variable ps 0.9 \
       lc rgb "black", \
     dem index 0 using "p_over_pe":"q_over_pe":"label" with labels hypertext point pt 7 ps 0.9 \
       lc rgb "#ff000000", \
     keyentry with points pt 7 ps 0.9 lc rgb "black" title "asymptotic states, detected", \
     keyentry with points pt 6 ps 0.9 lc rgb "black" title "still drifting"
unset key
unset logscale x
set format x "%g"
set xrange [0:x_hi]
set title "(b)"
plot @paths_b @models_b \
     dem index 0 using "p_over_pe":"q_over_pe":"point_type" with points pt variable ps 0.9 \
       lc rgb "black", \
     dem index 0 using "p_over_pe":"q_over_pe":"label" with labels hypertext point pt 7 ps 0.9 \
       lc rgb "#ff000000"
unset multiplot
