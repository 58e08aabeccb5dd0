# `granasym study compare` (b): ln(1+e) against p of the asymptotic states
# matched between studies A and B (data/compare_states.tsv: block 0 A,
# block 1 B; means with 95 % intervals in ln(1+e) and ln p, and a hover
# label; a thin grey line joins A's and B's mean of one state,
# data/compare_pairs.tsv), with each study's NCL (data/compare_ncl_a.tsv, _b.tsv) where it
# has one. Variables: title_a, title_b, has_ncl_a, has_ncl_b, ncl_title_a,
# ncl_title_b, x_min, x_max, y_min, y_max.
width = 9.0; height = 5.0
panels_right = 0.64
load scripts."/common.gp"
file = data."/compare_states.tsv"
set lmargin at screen 0.09
set rmargin at screen panels_right
set bmargin at screen 0.12
set tmargin at screen 0.95
set key at screen panels_right + 0.02, 0.95 left top Left reverse samplen 2.5 spacing 1.3 font ",8"
set logscale x
set format x "10^{%T}"
set xrange [x_min:x_max]
set yrange [y_min:y_max]
set xlabel label_p
set ylabel label_lnv
set bars small
# The NCLs are optional layers, macros (gnuplot reads a file even for an empty loop).
ncl_a = has_ncl_a > 0 ? 'data."/compare_ncl_a.tsv" using "p_kpa":"ln_1_plus_e" with lines lt 1 dt 2 lw 1.2 title ncl_title_a noenhanced,' : ''
ncl_b = has_ncl_b > 0 ? 'data."/compare_ncl_b.tsv" using "p_kpa":"ln_1_plus_e" with lines lt 2 dt 3 lw 1.5 title ncl_title_b noenhanced,' : ''
low(c, w) = column(c) - column(w)
high(c, w) = column(c) + column(w)
plot @ncl_a @ncl_b \
     data."/compare_pairs.tsv" using "p_kpa":"ln_1_plus_e" with lines lc rgb "#b0b0b0" lw 0.8 title "A and B of one state", \
     file index 0 using "p_kpa":"ln_1_plus_e":"p_low_kpa":"p_high_kpa":(low("ln_1_plus_e", "ln_1_plus_e_ci95")):(high("ln_1_plus_e", "ln_1_plus_e_ci95")) \
       with xyerrorbars lt 1 pt 7 ps 0.8 title title_a noenhanced, \
     file index 1 using "p_kpa":"ln_1_plus_e":"p_low_kpa":"p_high_kpa":(low("ln_1_plus_e", "ln_1_plus_e_ci95")):(high("ln_1_plus_e", "ln_1_plus_e_ci95")) \
       with xyerrorbars lt 2 pt 6 ps 0.8 lw 1.3 title title_b noenhanced, \
     keyentry with xyerrorbars lc rgb "#555555" pt -1 title "mean ± 95 % interval", \
     file index 0 using "p_kpa":"ln_1_plus_e":9 with labels hypertext point lt 1 pt 7 ps 0.8, \
     file index 1 using "p_kpa":"ln_1_plus_e":9 with labels hypertext point lt 2 pt 6 ps 0.8 lw 1.3
