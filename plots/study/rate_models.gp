# The rate study (e), issue 10 section 4: the quasi-static asymptotic states
# (point_type 7) beside the paper-rate ones (12) and the calibrated models.
# (a) psi_sigma against psi_epsilon: data/rate_models_quasi_static.tsv and
# data/rate_models_paper_rate.tsv (psi_epsilon_deg, psi_sigma_deg,
# psi_sigma_ci95; each when n_quasi_static, n_paper_rate > 0) and the models' curves
# (data/rate_models_curves.tsv); (b) ln(1+e) against p: data/rate_models_states.tsv
# (one block per psi_epsilon, then the drained states of the quasi-static set,
# point_type 9) and the models' lines (data/rate_models_lines.tsv).
# Variables: n_models, n_psi, psi_titles (words), quasi_title, n_quasi_static,
# n_paper_rate, psi_tics (the tics of (a) at the swept directions, a gnuplot
# tic list; empty: automatic) and with them psi_x_min, psi_x_max (the axis of (a)).
width = 11.0; height = 4.8
panels_right = 0.76
load scripts."/common.gp"
quasi = data."/rate_models_quasi_static.tsv"
paper = data."/rate_models_paper_rate.tsv"
states = data."/rate_models_states.tsv"
curves = data."/rate_models_curves.tsv"
lines = data."/rate_models_lines.tsv"
model_dt(m) = m + 2
quasi_a = n_quasi_static > 0 ? 'quasi using "psi_epsilon_deg":"psi_sigma_deg":"psi_sigma_ci95" with yerrorbars pt 7 ps 0.8 lc rgb "#1f77b4" title quasi_title,' : ''
paper_a = n_paper_rate > 0 ? 'paper using "psi_epsilon_deg":"psi_sigma_deg":"psi_sigma_ci95" with yerrorbars pt 12 ps 0.9 lc rgb "#d62728" title "constant ‖D‖ (paper rate)",' : ''
models_a = n_models > 0 ? 'for [m=0:n_models-1] curves index m using "psi_epsilon_deg":"psi_sigma_deg" with lines lc rgb "#555555" dt model_dt(m) lw 1 title columnheader(3),' : ''
models_b = n_models > 0 ? 'for [m=0:n_models-1] lines index m using "p_kpa":"ln_1_plus_e" with lines lc rgb "#555555" dt model_dt(m) lw 0.7 notitle,' : ''
set multiplot layout 1,2 margins 0.07,panels_right,0.12,0.92 spacing 0.09,0.1
set key at screen panels_right + 0.015, 0.92 left top Left reverse samplen 3 spacing 1.05 font ",8"
set xlabel label_psi_epsilon
set ylabel label_psi_sigma
set title "(a)"
if (strlen(psi_tics) > 0) eval "set xtics ".psi_tics; set xrange [psi_x_min:psi_x_max]
plot @models_a @quasi_a @paper_a \
     keyentry with points pt 7 lc rgb "black" title "(b): filled, the quasi-static set", \
     keyentry with points pt 12 lc rgb "black" title "(b): open, the paper rate"
set key at screen panels_right + 0.015, 0.55 left top Left reverse samplen 3 spacing 1.05 font ",8"
set xtics autofreq
set xrange [*:*]
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_lnv
set title "(b)"
plot @models_b for [i=0:n_psi-1] states index i using "p_kpa":"ln_1_plus_e":"point_type" \
       with points pt variable ps 0.8 lt (i+1) notitle, \
     for [i=0:n_psi-1] keyentry with points pt (word(psi_titles, i+1) eq "drained" ? 9 : 7) ps 0.8 lt (i+1) \
       title word(psi_titles, i+1)
unset multiplot
