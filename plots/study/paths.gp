# Path families (paper Figs. 10, 11, 13, 14, 15): (a) psi_sigma-p,
# (b) ln(1+e)-p, (c) psi_sigma-ln(1+e). Data (DIR/figures/data/<stem>_*.tsv):
#   _paths      one block per case: the replicates' mean path (p >= 0.5 kPa)
#   _bands      the mean paths' bands (± one standard error) as closed outlines (band_colours)
#   _tails      the rows below 0.5 kPa (a gas's tail), drawn faint
#   _unloading  the unloading paths to the OC starts (grey; n_unloading)
#   _replicates every replicate's path (when the figure settings ask for them)
#   _states     asymptotic states: detected, drifting, then reference states,
#               with a hover label (last column) for the SVG
#   _lines      the NCL fit and (where the paper draws it) the CSL fit
# Variables: stem, n_paths, path_colours, path_dashes (per path), colour_titles,
# dash_titles, colour_heading (the legend), n_bands, band_colours, bands_in_b,
# n_unloading, n_marks, n_own_marks, first_open,
# n_lines, line_titles, n_tails, tail_colours, n_replicates, replicate_colours and the axis
# ranges p_lo, p_hi, lnv_lo, lnv_hi, psi_lo, psi_hi (from the valid data).
width = 10.0; height = 7.5
load scripts."/common.gp"
paths = data."/".stem."_paths.tsv"
tails = data."/".stem."_tails.tsv"
marks = data."/".stem."_states.tsv"
lines = data."/".stem."_lines.tsv"
replicates = data."/".stem."_replicates.tsv"
# Marks: detected filled circles, drifting open circles, reference grey squares.
mark_pt(b) = b < n_own_marks ? (b == first_open ? 6 : 7) : 5
mark_lc(b) = b < n_own_marks ? "black" : "#aaaaaa"
mark_ps(b) = b < n_own_marks ? 0.7 : 0.6
colour(i) = int(word(path_colours, i+1))
dash(i) = int(word(path_dashes, i+1))
tail_colour(i) = int(word(tail_colours, i+1))
band_colour(i) = int(word(band_colours, i+1))
bands = data."/".stem."_bands.tsv"
B(y) = sprintf('for [i=0:n_bands-1] bands index i using "p_kpa":"%s" with filledcurves closed lt band_colour(i),', y)
bands_a = n_bands > 0 ? B("psi_sigma_edge") : ''
bands_b = n_bands > 0 && bands_in_b ? B("ln_1_plus_e_edge") : ''
unloading = data."/".stem."_unloading.tsv"
U(x, y) = sprintf('for [i=0:n_unloading-1] unloading index i using "%s":"%s" with lines lc rgb "#999999" lw 1,', x, y)
unload_a = n_unloading > 0 ? U("p_kpa", "psi_sigma_deg") : ''
unload_b = n_unloading > 0 ? U("p_kpa", "ln_1_plus_e") : ''
unload_c = n_unloading > 0 ? U("ln_1_plus_e", "psi_sigma_deg") : ''

replicate_colour(i) = int(word(replicate_colours, i+1))
line_dt(i) = i == 0 ? 2 : 4
# Optional layers are macros (gnuplot reads a file even for an empty loop).
L(x, y) = sprintf('for [b=0:n_marks-1] marks index b using "%s":"%s":"label" with labels hypertext point pt mark_pt(b) ps mark_ps(b) lc rgb mark_lc(b),', x, y)
marks_a = n_marks > 0 ? L("p_kpa", "psi_sigma_deg") : ''
marks_b = n_marks > 0 ? L("p_kpa", "ln_1_plus_e") : ''
marks_c = n_marks > 0 ? L("ln_1_plus_e", "psi_sigma_deg") : ''
T(x, y) = sprintf('for [i=0:n_tails-1] tails index i using "%s":"%s" with lines lt tail_colour(i) lw 0.5 dt 3,', x, y)
tails_a = n_tails > 0 ? T("p_kpa", "psi_sigma_deg") : ''
tails_b = n_tails > 0 ? T("p_kpa", "ln_1_plus_e") : ''
tails_c = n_tails > 0 ? T("ln_1_plus_e", "psi_sigma_deg") : ''
R(x, y) = sprintf('for [i=0:n_replicates-1] replicates index i using "%s":"%s" with lines lt replicate_colour(i) lw 0.4,', x, y)
reps_a = n_replicates > 0 ? R("p_kpa", "psi_sigma_deg") : ''
reps_b = n_replicates > 0 ? R("p_kpa", "ln_1_plus_e") : ''
reps_c = n_replicates > 0 ? R("ln_1_plus_e", "psi_sigma_deg") : ''
fits_b = n_lines > 0 ? 'for [i=0:n_lines-1] lines index i using "p_kpa":"ln_1_plus_e" with lines lc rgb "#333333" lw 1 dt line_dt(i),' : ''
# Panels (a)-(c) in a 2 x 2 grid; the legend fills the fourth cell.
set multiplot layout 2,2 margins 0.08,0.97,0.07,0.96 spacing 0.1,0.1
set style fill transparent solid 0.10 noborder
set logscale x
set format x "10^{%T}"
set xrange [p_lo:p_hi]
set xlabel label_p
set ylabel label_psi_sigma
set yrange [psi_lo:psi_hi]
set title "(a)"
plot @unload_a @bands_a @tails_a @reps_a \
     for [i=0:n_paths-1] paths index i using "p_kpa":"psi_sigma_deg" with lines lt colour(i) dt dash(i) lw 1.3, \
     @marks_a NaN notitle
set ylabel label_lnv
set yrange [lnv_lo:lnv_hi]
set title "(b)"
plot @unload_b @bands_b @tails_b @reps_b @fits_b \
     for [i=0:n_paths-1] paths index i using "p_kpa":"ln_1_plus_e" with lines lt colour(i) dt dash(i) lw 1.3, \
     @marks_b NaN notitle
unset logscale x
set format x "%g"
set xrange [lnv_lo:lnv_hi]
set xlabel label_lnv
set ylabel label_psi_sigma
set yrange [psi_lo:psi_hi]
set title "(c)"
plot @unload_c @tails_c @reps_c \
     for [i=0:n_paths-1] paths index i using "ln_1_plus_e":"psi_sigma_deg" with lines lt colour(i) dt dash(i) lw 1.3, \
     @marks_c NaN notitle
# The legend: colours (directions, or starts when all paths share one
# direction), dash types (starts), marks and fitted lines, in the fourth cell.
unset title; unset xlabel; unset ylabel; unset grid; unset border; unset tics
set xrange [0:1]; set yrange [0:1]
set key at screen 0.56, 0.45 left top Left reverse samplen 3 spacing 1.1 font ",8" maxrows 40 width 2
n_colours = words(colour_titles)
n_dashes = words(dash_titles)
plot 2 with lines lc rgb "white" notitle, keyentry with lines lt -2 lc rgb "white" title "{/:Bold ".colour_heading."}", \
     for [i=1:n_colours] keyentry with lines lt i lw 1.3 title word(colour_titles, i), \
     for [j=1:(n_dashes > 0 ? 1 : 0)] keyentry with lines lt -2 lc rgb "white" title "{/:Bold from}", \
     for [j=1:n_dashes] keyentry with lines lc rgb "#333333" dt j lw 1.3 title word(dash_titles, j), \
     for [b=1:n_marks] keyentry with points pt mark_pt(b-1) ps mark_ps(b-1) lc rgb mark_lc(b-1) title word(mark_titles, b), \
     for [i=1:n_unloading] keyentry with lines lc rgb "#999999" title "unloading (ψ_ε = 180°) to the OC starts", \
     for [i=1:n_lines] keyentry with lines lc rgb "#333333" dt line_dt(i-1) title word(line_titles, i)
unset multiplot
