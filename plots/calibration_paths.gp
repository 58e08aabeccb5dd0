# Whole paths of a calibration (issue 36 §3-4): each path dataset's DEM
# samples against the fitted model integrated along the DEM's own strain path
# from the DEM's initial state. One row per path: the stress path q-p, the
# stress ratio q/p and the void ratio e against the strain path length; an
# isotropic unload-reload path (kind unload_reload) instead e against p
# (log scale), p and e against the strain path length.
# Data written by `granasym calibrate` into its plot-data folder
# (paths.txt, path_<k>.csv); `calibrate` and `study calibrate` draw it as
# DIR/paths.png when gnuplot is on PATH.
# Usage: gnuplot -e "dir='CONFIG_plots'" plots/calibration_paths.gp   (writes dir/paths.png)
if (!exists("dir")) dir = "."
list = dir."/paths.txt"
n = int(system("wc -l < '".list."'"))
field(k, c) = system(sprintf("sed -n '%dp' '%s' | cut -f%d", k, list, c))
set terminal pngcairo size 1500,(360*n+60) font ",11"
set output dir."/paths.png"
set datafile separator ","
set grid
set style line 1 lc rgb "#1f77b4" pt 7 ps 0.8
set style line 2 lc rgb "#d62728" lw 2.5
set multiplot layout n,3 title "DEM paths (blue points) and the fitted model along them (red line)" font ",13"
do for [k=1:n] {
  f = dir."/".field(k, 1)
  set title field(k, 2) noenhanced
  s_label = "strain path length s = ∫‖dε‖ (-)"
  if (field(k, 3) eq "unload_reload") {
    set logscale x
    set xlabel "p (kPa, log scale)"
    set ylabel "void ratio e (-)"
    set key top right box opaque samplen 2 font ",10"
    plot f using "dem_p_kpa":"dem_e" with points ls 1 title "DEM", \
         f using "model_p_kpa":"model_e" with lines ls 2 title "model"
    unset logscale x
    set xlabel s_label
    set ylabel "p (kPa)"
    set key top left box opaque samplen 2 font ",10"
    plot f using "strain_path":"dem_p_kpa" with points ls 1 title "DEM", \
         f using "strain_path":"model_p_kpa" with lines ls 2 title "model"
  } else {
    set xlabel "p (kPa)"
    set ylabel "q (kPa)"
    set key bottom right box opaque samplen 2 font ",10"
    plot f using "dem_p_kpa":"dem_q_kpa" with points ls 1 title "DEM", \
         f using "model_p_kpa":"model_q_kpa" with lines ls 2 title "model"
    set xlabel s_label
    set ylabel "q/p (-)"
    plot f using "strain_path":"dem_q_over_p" with points ls 1 title "DEM", \
         f using "strain_path":"model_q_over_p" with lines ls 2 title "model"
  }
  set xlabel s_label
  set ylabel "void ratio e (-)"
  set key top right box opaque samplen 2 font ",10"
  plot f using "strain_path":"dem_e" with points ls 1 title "DEM", \
       f using "strain_path":"model_e" with lines ls 2 title "model"
}
unset multiplot
