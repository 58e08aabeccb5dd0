# The rate study (c): the critical-state stress ratio M = q/p of the
# psi_epsilon = 90 deg asymptotic states against the measured I(d_max)
# (data/rate_critical_state_groups.tsv: one block per Young's modulus and
# start; columns inertial_number, inertial_number_ci95, q_over_p,
# q_over_p_ci95, point_type, colour), the quasi-static lines M_0 + b I
# (data/rate_critical_state_fits.tsv) and limits M_0 at I -> 0, drawn at the
# left edge i_left (data/rate_critical_state_limits.tsv), both when
# n_fits > 0, and the literature band band_low..band_high.
# The groups are drawn at drawn_at: the measured I, or, when the drained
# cases' materials are series of their own (n_materials > 0, their titles
# and colours in material_titles and material_colours), 4 % apart per
# material.
# Variables: x_min, x_max, y_min, y_max (the axes), n_groups, n_fits, n_starts, start_titles (words, in colour
# order), n_materials, material_titles, material_colours, n_isochoric and n_drained (the blocks of
# psi_epsilon = 90 deg and drained groups: their shapes are keyed when present), modulus_note,
# band_low, band_high, i_left (with n_fits > 0 the left edge, labelled I → 0).
width = 8.0; height = 5.0
panels_right = 0.64
load scripts."/common.gp"
set lmargin at screen 0.1
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.92 left top Left reverse samplen 1 spacing 1.1 font ",8"
set logscale x
set format x "10^{%T}"
set xlabel "I(d_{max}) (–)"
set ylabel "M = q/p (–)"
set xrange [x_min:x_max]
set yrange [y_min:y_max]
set object 1 rect from graph 0, first band_low to graph 1, first band_high fc rgb "#e8e8e8" fs solid noborder behind
# The marks of I = 1e-2 and 1e-3, where the axis reaches them.
if (x_min < 1e-2 && x_max > 1e-2) set arrow 1 from 1e-2, graph 0 to 1e-2, graph 1 nohead dt 2 lc rgb "black"
if (x_min < 1e-3 && x_max > 1e-3) set arrow 2 from 1e-3, graph 0 to 1e-3, graph 1 nohead dt 3 lc rgb "#777777"
if (n_fits > 0) set label 1 "I → 0" at first i_left, graph 0.04 center font ",8"
groups = data."/rate_critical_state_groups.tsv"
fits = data."/rate_critical_state_fits.tsv"
limits = data."/rate_critical_state_limits.tsv"
fit_layer = n_fits > 0 ? 'for [b=0:n_fits-1] fits index b using "inertial_number":"q_over_p":"colour" with lines lc variable dt 2 lw 1, for [b=0:n_fits-1] limits index b using "inertial_number":"q_over_p":"q_over_p_ci95":"colour" with yerrorbars pt -1 lc variable lw 1, for [b=0:n_fits-1] limits index b using "inertial_number":"q_over_p":"point_type":"colour" with points pt variable lc variable ps 1.1,' : ''
plot @fit_layer \
     for [b=0:n_groups-1] groups index b using "drawn_at":"q_over_p":"inertial_number_ci95":"q_over_p_ci95":"colour" \
       with xyerrorbars pt -1 lc variable lw 0.7, \
     for [b=0:n_groups-1] groups index b using "drawn_at":"q_over_p":"point_type":"colour" \
       with points pt variable lc variable ps 0.9, \
     for [s=1:n_starts] keyentry with points pt 7 lt s title word(start_titles, s), \
     for [m=1:n_materials] keyentry with points pt 9 lt int(word(material_colours, m)) \
       title word(material_titles, m), \
     for [k=1:(n_isochoric > 0)] keyentry with points pt 7 lc rgb "black" title "fixed I*", \
     for [k=1:(n_isochoric > 0)] keyentry with points pt 13 lc rgb "black" title "constant ‖D‖", \
     for [k=1:(n_drained > 0)] keyentry with points pt 9 lc rgb "black" title "drained, constant σ_r", \
     for [k=1:(n_fits > 0)] keyentry with points pt 5 lc rgb "black" title "M_0 = M(I → 0)", \
     keyentry with boxes fc rgb "#e8e8e8" fs solid title sprintf("M = %g–%g (published, spheres)", band_low, band_high), \
     keyentry with points pt -1 lc rgb "white" title modulus_note
