# Paper Fig. 16: all asymptotic states, one colour per psi_epsilon
# (data/fig16_states.tsv: one block per psi_epsilon, point_type 7 detected,
# 6 drifting, a hover label last), with the study's and the calibrated
# models' NCL and CSL (data/fig16_model_lines.tsv; line_models: 0 for the
# study's, m for model m) and the models' psi_sigma(psi_epsilon)
# (data/fig16_model_curves.tsv, one block per model).
# (a) psi_sigma-p, (b) ln(1+e)-p, (c) psi_sigma-ln(1+e), (d) psi_sigma-psi_epsilon.
# Variables: n_states, state_titles, state_colours, n_lines, line_titles,
# line_models, n_models, model_titles, p_lo, p_hi, lnv_lo, lnv_hi.
width = 11.0; height = 7.5
panels_right = 0.72
load scripts."/common.gp"
states = data."/fig16_states.tsv"
lines = data."/fig16_model_lines.tsv"
curves = data."/fig16_model_curves.tsv"
colour(i) = int(word(state_colours, i+1))
line_model(i) = int(word(line_models, i+1))
# The study's lines black, each model's grey with its own dash type.
model_dt(m) = m + 1
line_lc(i) = line_model(i) == 0 ? "black" : "#777777"
line_dt(i) = line_model(i) == 0 ? 1 : model_dt(line_model(i))
line_lw(i) = line_model(i) == 0 ? 1.2 : 0.9
# Optional layers are macros (gnuplot reads a file even for an empty loop).
lines_b = n_lines > 0 ? 'for [i=0:n_lines-1] lines index i using "p_kpa":"ln_1_plus_e" with lines lc rgb line_lc(i) dt line_dt(i) lw line_lw(i),' : ''
models_d = n_models > 0 ? 'for [m=0:n_models-1] curves index m using "psi_epsilon_deg":"psi_sigma_deg" with lines lc rgb "#777777" dt model_dt(m+1) lw 1,' : ''
# Every state once as a coloured point, and once as an invisible hover label.
H(x, y) = sprintf('for [i=0:n_states-1] states index i using "%s":"%s":"label" with labels hypertext point pt 7 ps 0.8 lc rgb "#ff000000",', x, y)
hover_a = H("p_kpa", "psi_sigma_deg")
hover_b = H("p_kpa", "ln_1_plus_e")
hover_c = H("ln_1_plus_e", "psi_sigma_deg")
hover_d = H("psi_epsilon_deg", "psi_sigma_deg")
set multiplot layout 2,2 margins 0.07,panels_right,0.08,0.95 spacing 0.08,0.1
set logscale x
set format x "10^{%T}"
set xrange [p_lo:p_hi]
set xlabel label_p
set ylabel label_psi_sigma
set title "(a)"
plot for [i=0:n_states-1] states index i using "p_kpa":"psi_sigma_deg":"point_type" \
       with points pt variable ps 0.8 lt colour(i), @hover_a NaN notitle
set key at screen panels_right + 0.015, 0.95 left top Left reverse samplen 3 spacing 1.05 font ",8" width 2 maxrows 40
set ylabel label_lnv
set yrange [lnv_lo:lnv_hi]
set title "(b)"
plot @lines_b for [i=0:n_states-1] states index i using "p_kpa":"ln_1_plus_e":"point_type" \
       with points pt variable ps 0.8 lt colour(i), @hover_b \
     for [i=0:n_states-1] keyentry with points pt 7 ps 0.8 lt colour(i) title word(state_titles, i+1), \
     keyentry with points pt 7 lc rgb "black" title "detected", \
     keyentry with points pt 6 lc rgb "black" title "still drifting", \
     for [i=1:n_lines] keyentry with lines lc rgb line_lc(i-1) dt line_dt(i-1) lw line_lw(i-1) title word(line_titles, i), \
     for [m=1:n_models] keyentry with lines lc rgb "#777777" dt model_dt(m) title word(model_titles, m).": ψ_σ(ψ_ε)"
unset key
set autoscale y
unset logscale x
set format x "%g"
set xrange [lnv_lo:lnv_hi]
set xlabel label_lnv
set ylabel label_psi_sigma
set title "(c)"
plot for [i=0:n_states-1] states index i using "ln_1_plus_e":"psi_sigma_deg":"point_type" \
       with points pt variable ps 0.8 lt colour(i), @hover_c NaN notitle
set xrange [*:*]
set xlabel label_psi_epsilon
set title "(d)"
plot @models_d for [i=0:n_states-1] states index i using "psi_epsilon_deg":"psi_sigma_deg":"point_type" \
       with points pt variable ps 0.8 lt colour(i), @hover_d NaN notitle
unset multiplot
