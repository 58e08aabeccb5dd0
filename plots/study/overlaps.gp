# Paper Fig. 8: (a) relative-overlap histograms at the ends of the NCL's
# stages (data/fig08_histograms.tsv), (b) coordination number against p
# (data/fig08_contacts.tsv). Variables: n_histograms, has_contacts.
width = 10.0; height = 4.2
panels_right = 0.78
load scripts."/common.gp"
set multiplot layout 1,2 margins 0.07,panels_right,0.14,0.92 spacing 0.09,0.1
set key at screen panels_right + 0.015, 0.92 left top Left reverse samplen 2 spacing 1.05 font ",8"
set logscale x
set format x "10^{%T}"
set xlabel "Δu/(r_i + r_j) (–)"
set ylabel "fraction of contacts per bin (–)"
set title "(a)"
plot for [i=0:n_histograms-1] data."/fig08_histograms.tsv" index i \
       using "relative_overlap":"fraction" with linespoints pt 7 ps 0.5 lt (i+1) title columnheader(4)
unset key
set xlabel label_p
set ylabel "coordination number 2C/N (–)"
set title "(b)"
plot data."/fig08_contacts.tsv" index 0 using "p_kpa":"coordination" with lines lt 1
unset multiplot
