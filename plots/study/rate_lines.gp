# The rate study (b): ln(1+e) against p of the rate cases' asymptotic states
# (data/rate_lines_states.tsv: one block per psi_epsilon, Young's modulus and
# rate; columns p_kpa, ln_1_plus_e, point_type, colour) and the lines
# ln(1+e) = N - lambda ln p fitted through them (data/rate_lines_fits.tsv,
# when n_lines > 0; columns p_kpa, ln_1_plus_e, colour).
# The drained triaxial cases' critical states (σ_r = p_0, diamonds, coloured
# as the I* nearest their measured I) are blocks of the states file too;
# n_drained (0 or 1) says whether the key names them; n_ncl, n_csl, n_other
# (0 or 1) likewise for the directions' shapes. Drained materials that are
# series of their own (n_materials > 0) have their own colours and titles
# (material_colours, material_titles). The states are drawn at drawn_at: p,
# or 4 % apart per drained material.
# Variables: x_min, x_max, y_min, y_max (the axes), n_states, n_lines, n_rates, rate_titles (words, in colour
# order), n_drained, modulus_note.
width = 8.0; height = 5.0
panels_right = 0.66
load scripts."/common.gp"
set lmargin at screen 0.1
set rmargin at screen panels_right
set key at screen panels_right + 0.02, 0.92 left top Left reverse samplen 1 spacing 1.1 font ",8"
set logscale x
set format x "10^{%T}"
set xlabel label_p
set ylabel label_lnv
set xrange [x_min:x_max]
set yrange [y_min:y_max]
states = data."/rate_lines_states.tsv"
fits = data."/rate_lines_fits.tsv"
# Optional layers are macros (gnuplot reads a file even for an empty loop).
lines_layer = n_lines > 0 ? 'for [b=0:n_lines-1] fits index b using "p_kpa":"ln_1_plus_e":"colour" with lines lc variable lw 1,' : ''
plot @lines_layer \
     for [b=0:n_states-1] states index b using "drawn_at":"ln_1_plus_e":"point_type":"colour" \
       with points pt variable lc variable ps 0.8, \
     for [r=1:n_rates] keyentry with points pt 7 lt r title word(rate_titles, r), \
     for [m=1:n_materials] keyentry with points pt 13 lt int(word(material_colours, m)) \
       title word(material_titles, m), \
     for [k=1:n_ncl] keyentry with points pt 9 lc rgb "black" title "ψ_ε = 0° (NCL)", \
     for [k=1:n_csl] keyentry with points pt 7 lc rgb "black" title "ψ_ε = 90° (CSL)", \
     for [k=1:n_other] keyentry with points pt 5 lc rgb "black" title "other ψ_ε (e.g. NEL)", \
     for [d=1:n_drained] keyentry with points pt 13 lc rgb "black" title "drained: critical state, σ_r = p_0", \
     keyentry with points pt -1 lc rgb "white" title modulus_note
