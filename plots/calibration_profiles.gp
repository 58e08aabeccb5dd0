# Profile likelihoods of a calibration: for each profiled parameter the
# statistic D = 2 (cost - cost_min)/s^2 with the other parameters refitted
# (profiles.csv), its 95 % threshold (dashed), the fitted value (dotted) and
# the 95 % interval where D crosses the threshold (shaded); a parameter whose
# profile stays below the threshold to a bound or over a decade is "flat: not
# determined", with the side that crosses ("at most 0.0508, flat below")
# where only one does (profile_parameters.csv). Data written by `granasym calibrate`
# and `granasym study calibrate` into the plot-data folder.
# Usage: gnuplot -e "dir='CONFIG_plots'" plots/calibration_profiles.gp   (writes dir/profiles.png)
if (!exists("dir")) dir = "."
set datafile separator ","
set datafile columnheaders
table = dir."/profile_parameters.csv"
points = dir."/profiles.csv"
stats table using 2 nooutput
n = STATS_records
cols = n <= 3 ? n : (n <= 4 ? 2 : (n <= 6 ? 3 : 4))
rows = int(ceil(n * 1.0 / cols))
set terminal pngcairo size 360 * cols, 300 * rows font ",10"
set output dir."/profiles.png"
set multiplot layout rows, cols title "Profile likelihoods (95 %: D below the dashed line)"
set grid
set ylabel "D"
set key off
do for [b = 0:n - 1] {
  stats table every ::b::b using (name = strcol(1), is_log = column(2), opt = column(3), \
    thr = column(4), flat = column(5), low = column(6), high = column(7), \
    low_crossed = column(8), high_crossed = column(9), 0) nooutput
  if (is_log > 0.5) { set logscale x; set format x "%.2g" } else { unset logscale x; set format x "% g" }
  set xlabel name noenhanced
  # Flat on one side only (to a bound, a decade or the model's domain): the
  # side that crosses still bounds the parameter.
  one_sided = flat > 0.5 && (low_crossed > 0.5) != (high_crossed > 0.5)
  set title (flat <= 0.5 ? sprintf("[%.4g, %.4g]", low, high) : \
             !one_sided ? "flat: not determined" : \
             low_crossed > 0.5 ? sprintf("at least %.4g, flat above: not determined", low) : \
             sprintf("at most %.4g, flat below: not determined", high)) \
    textcolor rgb (flat > 0.5 ? "#d62728" : "black")
  set xrange [*:*]
  set yrange [*:*]
  stats points using (strcol(1) eq name ? column("value") : NaN) nooutput
  pad = is_log > 0.5 ? (STATS_max / STATS_min) ** 0.04 : 0.04 * (STATS_max - STATS_min)
  # A profile of one point (its first step already failed or left the bounds): a range about it.
  if (is_log > 0.5 && pad <= 1) { pad = 1.1 }
  if (is_log <= 0.5 && pad <= 0) { pad = STATS_max != 0 ? 0.04 * abs(STATS_max) : 0.04 }
  if (is_log > 0.5) {
    set xrange [STATS_min / pad:STATS_max * pad]
    # Four labelled tics evenly in ln x (a narrow log range has no decade to label).
    set xtics ()
    do for [t = 0:3] { v = STATS_min * (STATS_max / STATS_min) ** (t / 3.0); set xtics add (sprintf("%.3g", v) v) }
  } else {
    set xrange [STATS_min - pad:STATS_max + pad]
    set xtics autofreq
  }
  set yrange [0:4.5 * thr]
  set arrow 1 from opt, graph 0 to opt, graph 1 nohead dt 3 lc rgb "black"
  set object 1 rect from low, graph 0 to high, graph 1 behind \
    fc rgb (flat > 0.5 ? "#d62728" : "#2ca02c") fillstyle transparent solid 0.15 noborder
  plot points using (strcol(1) eq name ? column("value") : NaN):"statistic" \
         with linespoints pt 7 ps 0.6 lw 1.5 lc rgb "#1f77b4", \
       thr with lines dt 2 lw 1.5 lc rgb "#d62728"
  unset arrow 1
  unset object 1
}
unset multiplot
