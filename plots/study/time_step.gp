# Paper Sec. 5.2: the time step against a fifth of it: (a) the NCLs
# (data/<stem>_ncl.tsv), (b) psi_sigma against eps_s of the psi_epsilon = 90 deg paths
# (data/<stem>_paths.tsv). Variables: stem, n_ncl, n_paths.
width = 10.0; height = 4.2
panels_right = 0.72
load scripts."/common.gp"
ncl = data."/".stem."_ncl.tsv"
paths = data."/".stem."_paths.tsv"
set multiplot layout 1,2 margins 0.07,panels_right,0.14,0.92 spacing 0.09,0.1
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_lnv
set title "(a)"
set key at screen panels_right + 0.015, 0.92 left top Left reverse samplen 2 spacing 1.05 font ",8"
plot for [i=0:n_ncl-1] ncl index i using "p_kpa":"ln_1_plus_e" with lines lt (i+1) \
       title columnheader(3)
set key at screen panels_right + 0.015, 0.55 left top Left reverse samplen 2 spacing 1.05 font ",8"
unset logscale x
set format x "%g"
set xlabel label_eps_s
set ylabel label_psi_sigma
set title "(b)"
plot for [i=0:n_paths-1] paths index i using "eps_s":"psi_sigma_deg" with lines lt (i+3) \
       title columnheader(5)
unset multiplot
