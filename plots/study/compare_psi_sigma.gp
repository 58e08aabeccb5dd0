# `granasym study compare` (a): ψ_σ against ψ_ε of the asymptotic states
# matched between studies A and B (data/compare_states.tsv: block 0 A,
# block 1 B; per state the mean over the replicates, the half-width of its
# 95 % interval and, last, a hover label). A filled, B open and shifted by
# dx in ψ_ε so that both bars are seen; a thin grey line joins A's and B's
# mean of one state (data/compare_pairs.tsv). Variables: title_a, title_b, dx,
# x_min, x_max, y_min, y_max.
width = 9.0; height = 5.0
panels_right = 0.64
load scripts."/common.gp"
file = data."/compare_states.tsv"
set lmargin at screen 0.09
set rmargin at screen panels_right
set bmargin at screen 0.12
set tmargin at screen 0.95
set key at screen panels_right + 0.02, 0.95 left top Left reverse samplen 1.5 spacing 1.3 font ",8"
set xrange [x_min:x_max]
set yrange [y_min:y_max]
set xtics 15
set xlabel label_psi_epsilon
set ylabel label_psi_sigma
set bars small
plot data."/compare_pairs.tsv" using "psi_epsilon_deg":"psi_sigma_deg" with lines lc rgb "#b0b0b0" lw 0.8 title "A and B of one state", \
     file index 0 using "psi_epsilon_deg":"psi_sigma_deg":"psi_sigma_ci95" \
       with yerrorbars lt 1 pt 7 ps 0.8 title title_a noenhanced, \
     file index 1 using (column("psi_epsilon_deg") + dx):"psi_sigma_deg":"psi_sigma_ci95" \
       with yerrorbars lt 2 pt 6 ps 0.8 lw 1.3 title title_b noenhanced, \
     keyentry with yerrorbars lc rgb "#555555" pt -1 title "mean ± 95 % interval", \
     file index 0 using "psi_epsilon_deg":"psi_sigma_deg":9 \
       with labels hypertext point lt 1 pt 7 ps 0.8, \
     file index 1 using (column("psi_epsilon_deg") + dx):"psi_sigma_deg":9 \
       with labels hypertext point lt 2 pt 6 ps 0.8 lw 1.3
