# The rate study (a): the asymptotic psi_sigma against p, one panel per
# psi_epsilon and a last one of the drained cases when the study has them
# (data/rate_psi_sigma_<k>.tsv, k = 1..n_panels: one block per Young's
# modulus and rate, rows by start; columns p_kpa, p_ci95,
# psi_sigma_deg, psi_sigma_ci95, point_type, colour), means with their 95 %
# intervals, one colour per rate.
# Variables: n_panels, panel_titles, panel_blocks and the axis ranges
# panel_x_min, panel_x_max, panel_y_min, panel_y_max (words, one per panel),
# n_rates, rate_titles (words, in colour order), n_materials (0 unless the
# drained cases' materials are series of their own, one colour each),
# material_titles and material_colours (words), modulus_note. The points are
# drawn at the column drawn_at: p, or 4 % apart per material in the drained
# panel when the materials are series of their own.
width = 4.2*n_panels + 2.6; height = 4.2
panels_right = 1.0 - 2.6/width
load scripts."/common.gp"
set multiplot layout 1,n_panels margins 0.7/width,panels_right,0.13,0.9 spacing 0.75/width,0
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_psi_sigma
do for [k=1:n_panels] {
  set xrange [real(word(panel_x_min, k)):real(word(panel_x_max, k))]
  set yrange [real(word(panel_y_min, k)):real(word(panel_y_max, k))]
  file = sprintf("%s/rate_psi_sigma_%d.tsv", data, k)
  nb = int(word(panel_blocks, k))
  set title word(panel_titles, k)
  if (k == n_panels) {
    set key at screen panels_right + 0.02, 0.9 left top Left reverse samplen 1 spacing 1.1 font ",8"
    plot for [b=0:nb-1] file index b using "drawn_at":"psi_sigma_deg":"colour" with lines lc variable lw 0.8, \
         for [b=0:nb-1] file index b using "drawn_at":"psi_sigma_deg":"p_ci95":"psi_sigma_ci95":"colour" \
           with xyerrorbars pt -1 lc variable lw 0.7, \
         for [b=0:nb-1] file index b using "drawn_at":"psi_sigma_deg":"point_type":"colour" \
           with points pt variable lc variable ps 0.9, \
         for [r=1:n_rates] keyentry with points pt 7 lt r title word(rate_titles, r), \
         for [m=1:n_materials] keyentry with points pt 9 lt int(word(material_colours, m)) \
           title word(material_titles, m), \
         keyentry with points pt -1 lc rgb "white" title modulus_note
  } else {
    unset key
    plot for [b=0:nb-1] file index b using "drawn_at":"psi_sigma_deg":"colour" with lines lc variable lw 0.8, \
         for [b=0:nb-1] file index b using "drawn_at":"psi_sigma_deg":"p_ci95":"psi_sigma_ci95":"colour" \
           with xyerrorbars pt -1 lc variable lw 0.7, \
         for [b=0:nb-1] file index b using "drawn_at":"psi_sigma_deg":"point_type":"colour" \
           with points pt variable lc variable ps 0.9
  }
}
unset multiplot
