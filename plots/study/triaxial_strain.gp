# Paper Fig. 12: drained triaxial paths, (a) psi_sigma and (b) psi_epsilon
# against the shear strain (data/fig12_paths.tsv). Variables: n_paths,
# path_colours (one per sigma_r), path_dashes (1 from NC, 2 from OC states).
width = 10.0; height = 4.2
panels_right = 0.76
load scripts."/common.gp"
file = data."/fig12_paths.tsv"
colour(i) = int(word(path_colours, i+1))
dash(i) = int(word(path_dashes, i+1))
set multiplot layout 1,2 margins 0.07,panels_right,0.14,0.92 spacing 0.09,0.1
set key at screen panels_right + 0.015, 0.92 left top Left reverse samplen 2 spacing 1.05 font ",8"
set xlabel label_eps_s
set ylabel label_psi_sigma
set title "(a)"
plot for [i=0:n_paths-1] file index i using "eps_s":"psi_sigma_deg" with lines lt colour(i) dt dash(i) \
       title columnheader(4)
unset key
set ylabel label_psi_epsilon
set title "(b)"
plot for [i=0:n_paths-1] file index i using "eps_s":"psi_epsilon_deg" with lines lt colour(i) dt dash(i), \
     90 with lines dt 2 lc rgb "#777777"
unset multiplot
