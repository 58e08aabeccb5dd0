# Settings shared by the study figures (plots/study/*.gp). Each script sets
# `width` and `height` (inches) and loads this file. Variables given by
# `granasym study figures` in each figure's wrapper DIR/figures/<stem>.plt
# (redraw with `gnuplot DIR/figures/<stem>.plt`):
#   data    folder of the data files (DIR/figures/data)
#   out     output path without extension (DIR/figures/<stem>)
#   term    'png', 'pdf' or 'svg' (the SVG with hover labels on the states)
#   scripts this folder (for `load`)
# Data files: tab-separated blocks, two blank lines apart (gnuplot `index`);
# each block's header names the columns, its last field is the legend title.
if (!exists("term")) term = "png"
if (!exists("width")) width = 10.0
if (!exists("height")) height = 4.0
if (term eq "pdf") {
  set terminal pdfcairo enhanced color size width,height font "Sans,8" linewidth 1.5
}
if (term eq "svg") {
  set terminal svg enhanced size int(width*96),int(height*96) font "Sans,9" linewidth 1.2 mouse standalone
}
if (term eq "png") {
  set terminal pngcairo enhanced size int(width*110),int(height*110) font "Sans,9" linewidth 1.5
}
set output out.".".term
set encoding utf8
set datafile separator "\t"
set grid lc rgb "#dddddd"
set border lc rgb "#444444"
set key noautotitle
# Colours (Tableau 10), cycling.
set linetype 1 lc rgb "#1f77b4" pt 7
set linetype 2 lc rgb "#ff7f0e" pt 7
set linetype 3 lc rgb "#2ca02c" pt 7
set linetype 4 lc rgb "#d62728" pt 7
set linetype 5 lc rgb "#9467bd" pt 7
set linetype 6 lc rgb "#8c564b" pt 7
set linetype 7 lc rgb "#e377c2" pt 7
set linetype 8 lc rgb "#7f7f7f" pt 7
set linetype 9 lc rgb "#bcbd22" pt 7
set linetype 10 lc rgb "#17becf" pt 7
set linetype cycle 10
# Axis labels, with units.
label_p = "p (kPa)"
label_psi_sigma = "ψ_σ (°)"
label_psi_epsilon = "ψ_ε (°)"
label_lnv = "ln(1+e) (–)"
label_eps_s = "ε_s (–)"
label_q = "q (kPa)"
label_p_norm = "p/p_e^* (–)"
label_q_norm = "q/p_e^* (–)"
# The legend goes into the right-hand part of the canvas, outside every
# panel: panels use the screen from 0 to `panels_right`.
if (!exists("panels_right")) panels_right = 0.70
