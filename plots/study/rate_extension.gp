# The rate study (d): the extension sweep (issue 10 section 3). sigma_r/p of
# the asymptotic states against psi_epsilon (data/rate_extension_steps.tsv:
# one block per sweep, columns psi_epsilon_deg, sigma_r_over_p,
# sigma_r_over_p_ci95, colour), the liquefied steps on the zero line
# (data/rate_extension_liquefied.tsv) and psi_epsilon(d) with its interval
# (data/rate_extension_limits.tsv), each when its count is > 0.
# Variables: x_min, x_max, y_min, y_max, n_steps, n_liquefied, n_limits,
# n_sweeps, sweep_titles (words, in colour order).
width = 8.0; height = 5.0
panels_right = 0.62
load scripts."/common.gp"
set lmargin at screen 0.1
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.92 left top Left reverse samplen 1 spacing 1.1 font ",8"
set xlabel "ψ_ε (°)"
set ylabel "σ_r / p (–)"
set xrange [x_min:x_max]
set yrange [y_min:y_max]
set arrow 1 from graph 0, first 0 to graph 1, first 0 nohead dt 2 lc rgb "black"
set label 1 "limit d: σ_r = 0 (ψ_σ = 54.74°)" at graph 0.98, first 0 right offset 0, 1.2 font ",8"
steps = data."/rate_extension_steps.tsv"
liquefied = data."/rate_extension_liquefied.tsv"
limits = data."/rate_extension_limits.tsv"
step_layer = n_steps > 0 ? 'for [b=0:n_steps-1] steps index b using "psi_epsilon_deg":"sigma_r_over_p":"sigma_r_over_p_ci95":"colour" with yerrorbars pt 7 ps 0.8 lc variable lw 0.8, for [b=0:n_steps-1] steps index b using "psi_epsilon_deg":"sigma_r_over_p":"colour" with lines lc variable lw 1,' : ''
liquefied_layer = n_liquefied > 0 ? 'for [b=0:n_liquefied-1] liquefied index b using "psi_epsilon_deg":"sigma_r_over_p":"colour" with points pt 2 ps 1.4 lw 2 lc variable,' : ''
limit_layer = n_limits > 0 ? 'for [b=0:n_limits-1] limits index b using "psi_epsilon_deg":"sigma_r_over_p":"psi_epsilon_ci95":"colour" with xerrorbars pt 5 ps 1.1 lc variable lw 1.2,' : ''
plot @step_layer @liquefied_layer @limit_layer \
     for [s=1:n_sweeps] keyentry with points pt 7 lt s title word(sweep_titles, s), \
     for [k=1:(n_liquefied > 0)] keyentry with points pt 2 lc rgb "black" title "liquefied (most replicates)", \
     for [k=1:(n_limits > 0)] keyentry with points pt 5 lc rgb "black" title "ψ_ε(d) ± 95 %"
