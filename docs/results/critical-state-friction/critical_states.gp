# What sets M (issue 39 §2): the critical state of drained triaxial compression at
# sigma_r = 100 kPa and I(d_max) = 1e-3 for each material, 95 % intervals over three replicates.
#   gnuplot critical_states.gp      (reads critical_states.csv, writes critical_states.png)
set terminal pngcairo size 1200,520 font "DejaVu Sans,11"
set output "critical_states.png"
set datafile separator ","
set label 99 "Drained triaxial compression to the critical state at σ_r = 100 kPa, I(d_{max}) = 10^{-3}; E = 500 MPa, contact friction angle 0.5 rad; 5000 spheres (commit fb649ff)" at screen 0.5,0.04 center font ",10"
set multiplot layout 1,2 margins 0.07,0.95,0.27,0.90 spacing 0.09
set xrange [-0.6:5.6]
set xtics rotate by -25 left nomirror font ",10"
set grid ytics lc rgb "#dddddd"
set key top left box opaque font ",10"
set title "(a) critical-state stress ratio M = q/p"
set ylabel "M (-)"
set yrange [0.66:1.04]
# Published band for frictional spheres (analysis/rate_options.h) and the rate study's quasi-static limit.
set object 1 rect from -0.6,0.81 to 5.6,0.95 fc rgb "#e6e6e6" fs solid 1.0 noborder behind
set object 2 rect from -0.6,0.756 to 5.6,0.782 fc rgb "#cfe3f3" fs solid 1.0 noborder behind
plot keyentry with boxes fs solid 1.0 fc rgb "#e6e6e6" title "published, frictional spheres: 0.81–0.95", \
     keyentry with boxes fs solid 1.0 fc rgb "#cfe3f3" title "rate study, I → 0 (σ_r = 5–500 kPa): 0.769 ± 0.013", \
     "critical_states.csv" using 0:"q_over_p_mean":"q_over_p_ci95":xtic(1) \
       with yerrorbars pt 7 ps 1.4 lw 2 lc rgb "#c0392b" title "DEM, 3 replicates, 95 % interval"
unset object 1
unset object 2
unset label 99
set title "(b) void ratio at the critical state, p = 133-135 kPa"
set ylabel "ln(1+e) (-)"
set yrange [0.455:0.545]
plot "critical_states.csv" using 0:"ln_1_plus_e_mean":"ln_1_plus_e_ci95":xtic(1) \
       with yerrorbars pt 7 ps 1.4 lw 2 lc rgb "#c0392b" title "DEM, 3 replicates, 95 % interval"
unset multiplot
