# Paper Fig. 5: a model's paths A (compression), B (isochoric) and C
# (extension) from normally and overconsolidated states (data/<paths_file>,
# one block per element test). Variables: n_paths, paths_file.
width = 10.0; height = 7.5
load scripts."/common.gp"
if (!exists("paths_file")) paths_file = "fig05_paths.tsv"
file = data."/".paths_file
start_dt(i) = i%2 + 1
# Panels (a)-(c) in a 2 x 2 grid; the legend fills the fourth cell.
set multiplot layout 2,2 margins 0.08,0.97,0.07,0.96 spacing 0.1,0.1
set key at screen 0.58, 0.44 left top Left reverse samplen 3 spacing 1.1 font ",9"
# Colour by path (A, B, C: two tests each), dash by the start.
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_psi_sigma
set title "(a)"
plot for [i=0:n_paths-1] file index i using "p_kpa":"psi_sigma_deg" with lines \
       lt (i/2+1) dt start_dt(i) title columnheader(4)
unset key
set ylabel label_lnv
set title "(b)"
plot for [i=0:n_paths-1] file index i using "p_kpa":"ln_1_plus_e" with lines lt (i/2+1) dt start_dt(i)
unset logscale x
set format x "%g"
set xlabel label_lnv
set ylabel label_psi_sigma
set title "(c)"
plot for [i=0:n_paths-1] file index i using "ln_1_plus_e":"psi_sigma_deg" with lines \
       lt (i/2+1) dt start_dt(i)
unset multiplot
