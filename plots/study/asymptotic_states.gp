# Paper Fig. 16: all asymptotic states, one colour per psi_epsilon
# (data/fig16_states.tsv; point_type 7 detected, 6 drifting), with the
# calibrated models' asymptotic lines (data/fig16_model_lines.tsv) and
# psi_sigma(psi_epsilon) (data/fig16_model_curves.tsv), one block per model.
# (a) psi_sigma-p, (b) ln(1+e)-p, (c) psi_sigma-ln(1+e), (d) psi_sigma-psi_epsilon.
# Variables: n_states, state_titles (quoted words), n_models.
width = 11.0; height = 7.5
panels_right = 0.74
load scripts."/common.gp"
states = data."/fig16_states.tsv"
lines = data."/fig16_model_lines.tsv"
curves = data."/fig16_model_curves.tsv"
model_dt(m) = m + 2
# Optional layers are macros (gnuplot reads a file even for an empty loop).
models_a = n_models > 0 ? 'for [m=0:n_models-1] lines index m using "p_kpa":"psi_sigma_deg" with lines lc rgb "#555555" dt model_dt(m) lw 0.7,' : ''
models_b = n_models > 0 ? 'for [m=0:n_models-1] lines index m using "p_kpa":"ln_1_plus_e" with lines lc rgb "#555555" dt model_dt(m) lw 0.7 title columnheader(4),' : ''
models_d = n_models > 0 ? 'for [m=0:n_models-1] curves index m using "psi_epsilon_deg":"psi_sigma_deg" with lines lc rgb "#555555" dt model_dt(m) lw 1,' : ''
set multiplot layout 2,2 margins 0.07,panels_right,0.08,0.95 spacing 0.08,0.1
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_psi_sigma
set title "(a)"
plot @models_a for [i=0:n_states-1] states index i using "p_kpa":"psi_sigma_deg":"point_type" \
       with points pt variable ps 0.8 lt (i+1)
set key at screen panels_right + 0.015, 0.95 left top Left reverse samplen 3 spacing 1.05 font ",8"
set ylabel label_lnv
set title "(b)"
plot for [i=0:n_states-1] states index i using "p_kpa":"ln_1_plus_e":"point_type" \
       with points pt variable ps 0.8 lt (i+1), \
     for [i=0:n_states-1] keyentry with points pt 7 ps 0.8 lt (i+1) title word(state_titles, i+1), \
     @models_b keyentry with points pt 7 lc rgb "black" title "detected", \
     keyentry with points pt 6 lc rgb "black" title "still drifting"
unset key
unset logscale x
set format x "%g"
set xlabel label_lnv
set ylabel label_psi_sigma
set title "(c)"
plot for [i=0:n_states-1] states index i using "ln_1_plus_e":"psi_sigma_deg":"point_type" \
       with points pt variable ps 0.8 lt (i+1)
set xlabel label_psi_epsilon
set title "(d)"
plot @models_d for [i=0:n_states-1] states index i using "psi_epsilon_deg":"psi_sigma_deg":"point_type" \
       with points pt variable ps 0.8 lt (i+1)
unset multiplot
