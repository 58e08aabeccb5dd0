# Work-precision figure of the constitutive integrators (issue 3, §6): error
# against median run time, log–log, one curve per integrator, one panel per
# path and model, from the CSV of bench/constitutive_work_precision.
#
#   gnuplot -e "csv='constitutive_work_precision.csv'; png='work_precision.png'" \
#       plots/work_precision.gp
#
# Only rows with status "ok" are drawn; the dashed grey line is the reference
# solution's own convergence check (its difference to a run with ten times
# tighter tolerances): errors below it are not resolved.

if (!exists("csv")) csv = "constitutive_work_precision.csv"
if (!exists("png")) png = "work_precision.png"

paths = "isotropic_nc isochoric_nc isochoric_ocr8 drained_triaxial proportional_45 proportional_100 unload_reload"
titles = "'isotropic NC' 'isochoric from NC' 'isochoric from OCR 8' 'drained triaxial' 'proportional 45°' 'proportional 100°' 'unload–reload'"
models = "hypoplastic_clay modified_cam_clay"
model_titles = "'hypoplastic clay' 'Cam clay'"
methods = "rkf23 cvode_bdf_exact cvode_bdf_fd cvode_adams arkode_erk arkode_erk_order3 arkode_erk_order5 arkode_erk_order8 arkode_dirk stress_point_modified_euler stress_point_return_mapping"
labels = "'RKF23 (baseline)' 'CVODE BDF, exact J' 'CVODE BDF, FD J' 'CVODE Adams' 'ARKODE ERK 4' 'ARKODE ERK 3' 'ARKODE ERK 5 (default)' 'ARKODE ERK 8' 'ARKODE DIRK 4' 'stress point: modified Euler' 'stress point: return mapping'"
colors = "#000000 #1f77b4 #6baed6 #2ca02c #ff7f0e #fdae6b #d62728 #9467bd #8c564b #e377c2 #7f7f7f"
array point_types[11] = [7, 5, 4, 9, 13, 12, 11, 15, 3, 1, 2]

# Rows of one curve as "time error"; tolerance order is the CSV's.
curve(p, m, i) = sprintf("< awk -F, '$1==\"%s\" && $2==\"%s\" && $3==\"%s\" && $9==\"ok\" {print $6, $5}' %s", p, m, i, csv)
check(p, m) = real(system(sprintf("awk -F, 'BEGIN {v = 1e-16} $1==\"%s\" && $2==\"%s\" && $3==\"reference_self_check\" && $5 > v {v = $5} END {print v}' %s", p, m, csv)))

set terminal pngcairo size 2400,2100 font "DejaVu Sans,11"
set output png
set multiplot layout 4,4 title "Run time against error: max relative deviation from the reference over the recorded path (median of repeats)" font ",15"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set xlabel "run time (s)"
set ylabel "error"
set yrange [1e-11:1]
unset key

do for [mi = 1:2] {
  model = word(models, mi)
  do for [pi = 1:7] {
    path = word(paths, pi)
    set title sprintf("%s — %s", word(model_titles, mi), word(titles, pi))
    floor = check(path, model)
    set arrow 1 from graph 0, first floor to graph 1, first floor nohead dt 2 lc rgb "#999999"
    count = (mi == 1) ? 9 : words(methods)  # the stress-point methods are Cam clay's only
    plot for [k = 1:count] curve(path, model, word(methods, k)) using 1:2 \
         with linespoints lw 2 pt point_types[k] ps 1.1 lc rgb word(colors, k) title word(labels, k)
    unset arrow 1
  }
  # The legend in the eighth panel of each model's row block.
  set title sprintf("%s: legend", word(model_titles, mi))
  unset border; unset tics; unset xlabel; unset ylabel; unset grid
  set key center center box spacing 1.4 font ",13"
  set xrange [1:2]
  set yrange [1:2]
  last = (mi == 1) ? 9 : words(methods)
  plot for [k = 1:last] 1e9 with linespoints lw 2 pt point_types[k] lc rgb word(colors, k) title word(labels, k)
  unset key; set border; set tics; set xlabel "run time (s)"; set ylabel "error"
  set grid xtics ytics mxtics mytics lc rgb "#dddddd"
  set autoscale x
  set yrange [1e-11:1]
}
unset multiplot
