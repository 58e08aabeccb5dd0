# `granasym study compare` (c): the difference B − A of ψ_σ (left) and
# ln(1+e) (right) of every matched asymptotic state with its 95 % Welch
# interval (data/compare_differences.tsv: one row per state at y, the
# differences, their half-widths, a class per quantity — 0 the interval
# leaves out 0, 1 it holds 0, 2 no interval — and a hover label). States are
# grouped by sample and kind, a bold header above each group. Variables:
# height (inches, from the number of rows), tics (the states' y tics),
# headers and header_y (the groups' titles as quoted words and their y),
# group_lines (y of the lines between groups), y_min, y_max, psi_min,
# psi_max, lnv_min, lnv_max, title (which study is A, which B), n_none
# (states without an interval: their legend entry is shown only then).
width = 10.0
load scripts."/common.gp"
file = data."/compare_differences.tsv"
top = 1 - 0.75 / height
bottom = 0.55 / height
set multiplot
set tmargin at screen top
set bmargin at screen bottom
set yrange [y_min:y_max]
eval "set ytics ".tics
set ytics noenhanced font ",7" scale 0
set grid xtics noytics
set mxtics 2
set style line 11 lc rgb "#c0392b" pt 7 ps 0.7
set style line 12 lc rgb "#2c3e50" pt 6 ps 0.7
set style line 13 lc rgb "#8c8c8c" pt 2 ps 0.7
set label 1 title at screen 0.5, 1 - 0.15 / height center noenhanced font ",9"
set key at screen 0.02, 1 - 0.3 / height left top vertical Left reverse samplen 1.5 font ",8"
set bars small
do for [i = 1:words(header_y)] {
  set label 100 + i word(headers, i) at graph 0, first real(word(header_y, i)) right offset -0.8, 0 font "Sans:Bold,7"
}
do for [i = 1:words(group_lines)] {
  y = real(word(group_lines, i))
  set arrow 100 + i from graph 0, first y to graph 1, first y nohead lc rgb "#bbbbbb" dt 2
}
set arrow 1 from first 0, graph 0 to first 0, graph 1 nohead lc rgb "#333333" lw 1 back
cls(c, k) = column(c) == k ? 1 : NaN
set lmargin at screen 0.24
set rmargin at screen 0.60
set xrange [psi_min:psi_max]
set xlabel "B − A of ψ_σ (°)"
plot file using (cls("psi_class", 0) * column("d_psi_sigma")):"y":"d_psi_sigma_ci95" with xerrorbars ls 11 title "95 % interval leaves out 0: differs", \
     file using (cls("psi_class", 1) * column("d_psi_sigma")):"y":"d_psi_sigma_ci95" with xerrorbars ls 12 title "interval holds 0", \
     file using (cls("psi_class", 2) * column("d_psi_sigma")):"y" with points ls 13 title (n_none > 0 ? "no interval (one replicate each)" : ""), \
     for [k = 0:2] file using (cls("psi_class", k) * column("d_psi_sigma")):"y":8 with labels hypertext point ls 11 + k
unset key
unset label
unset ytics
set lmargin at screen 0.63
set rmargin at screen 0.97
set xrange [lnv_min:lnv_max]
set xlabel "B − A of ln(1+e) (–)"
plot file using (cls("lnv_class", 0) * column("d_ln_1_plus_e")):"y":"d_ln_1_plus_e_ci95" with xerrorbars ls 11, \
     file using (cls("lnv_class", 1) * column("d_ln_1_plus_e")):"y":"d_ln_1_plus_e_ci95" with xerrorbars ls 12, \
     file using (cls("lnv_class", 2) * column("d_ln_1_plus_e")):"y" with points ls 13, \
     for [k = 0:2] file using (cls("lnv_class", k) * column("d_ln_1_plus_e")):"y":8 with labels hypertext point ls 11 + k
unset multiplot
