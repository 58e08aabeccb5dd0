# Path families (paper Figs. 10, 11, 13, 14, 15): (a) psi_sigma-p,
# (b) ln(1+e)-p, (c) psi_sigma-ln(1+e), one curve per case (data/<stem>_paths.tsv),
# with the asymptotic states marked (data/<stem>_states.tsv: detected,
# drifting, then reference states, as many blocks as are non-empty).
# Variables: stem, n_paths, n_marks, n_own_marks, first_open, path_colours and
# path_dashes (per path: colour by direction, dash type by start; see common.gp).
width = 10.0; height = 7.5
load scripts."/common.gp"
paths = data."/".stem."_paths.tsv"
marks = data."/".stem."_states.tsv"
# Marks: detected filled circles, drifting open circles, reference grey squares.
mark_pt(b) = b < n_own_marks ? (b == first_open ? 6 : 7) : 4
mark_lc(b) = b < n_own_marks ? "black" : "#999999"
# Optional layers are macros (gnuplot reads a file even for an empty loop).
marks_a = n_marks > 0 ? 'for [b=0:n_marks-1] marks index b using "p_kpa":"psi_sigma_deg" with points pt mark_pt(b) ps 0.8 lc rgb mark_lc(b) title columnheader(4),' : ''
marks_b = n_marks > 0 ? 'for [b=0:n_marks-1] marks index b using "p_kpa":"ln_1_plus_e" with points pt mark_pt(b) ps 0.8 lc rgb mark_lc(b),' : ''
marks_c = n_marks > 0 ? 'for [b=0:n_marks-1] marks index b using "ln_1_plus_e":"psi_sigma_deg" with points pt mark_pt(b) ps 0.8 lc rgb mark_lc(b),' : ''
colour(i) = int(word(path_colours, i+1))
dash(i) = int(word(path_dashes, i+1))
# Panels (a)-(c) in a 2 x 2 grid; the legend fills the fourth cell.
set multiplot layout 2,2 margins 0.08,0.97,0.07,0.96 spacing 0.1,0.1
set key at screen 0.58, 0.44 left top Left reverse samplen 3 spacing 1.05 font ",8" maxrows 24
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_psi_sigma
set title "(a)"
plot @marks_a for [i=0:n_paths-1] paths index i using "p_kpa":"psi_sigma_deg" with lines \
       lt colour(i) dt dash(i) title columnheader(7)
unset key
set ylabel label_lnv
set title "(b)"
plot @marks_b for [i=0:n_paths-1] paths index i using "p_kpa":"ln_1_plus_e" with lines lt colour(i) dt dash(i)
unset logscale x
set format x "%g"
set xlabel label_lnv
set ylabel label_psi_sigma
set title "(c)"
plot @marks_c for [i=0:n_paths-1] paths index i using "ln_1_plus_e":"psi_sigma_deg" \
       with lines lt colour(i) dt dash(i)
unset multiplot
