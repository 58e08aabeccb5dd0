# Paper Fig. 19: states picked along drained triaxial paths where their
# psi_epsilon reaches that of a constant-psi_epsilon path (point_type 8,
# open triangles) against those paths' asymptotic states (7, circles),
# one block per psi_epsilon (data/fig19_states.tsv): (a) psi_sigma-ln(1+e),
# (b) ln(1+e)-p. Variables: n_directions, direction_titles (quoted words),
# direction_colours (the colours of Fig. 16's directions).
width = 10.0; height = 4.5
panels_right = 0.78
load scripts."/common.gp"
file = data."/fig19_states.tsv"
colour(i) = int(word(direction_colours, i+1))
set multiplot layout 1,2 margins 0.07,panels_right,0.13,0.92 spacing 0.09,0.1
set key at screen panels_right + 0.015, 0.92 left top Left reverse samplen 2 spacing 1.05 font ",8"
set xlabel label_lnv
set ylabel label_psi_sigma
set title "(a)"
plot for [i=0:n_directions-1] file index i using "ln_1_plus_e":"psi_sigma_deg":"point_type" \
       with points pt variable ps 0.9 lt colour(i), \
     for [i=0:n_directions-1] keyentry with points pt 7 ps 0.9 lt colour(i) title word(direction_titles, i+1), \
     keyentry with points pt 7 lc rgb "black" title "asymptotic state", \
     keyentry with points pt 8 lc rgb "black" title "on a triaxial path"
unset key
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_lnv
set title "(b)"
plot for [i=0:n_directions-1] file index i using "p_kpa":"ln_1_plus_e":"point_type" \
       with points pt variable ps 0.9 lt colour(i)
unset multiplot
