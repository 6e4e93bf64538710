# Stability against stiffness: the largest stable step of every fixed-step
# method against the Type1 stiffness ks (points: measured, the stability
# search's largest stable step; dashed: the spectrum's prediction for the
# explicit methods).  Implicit methods stable at the search's largest step
# sit on the cap dt_max.
# Variables: dir (NAME.dat: ks stable unstable predicted), names,
# title_text.
load "plots/common.gp"
set logscale xy
set xlabel "Type1 stiffness ks (N/m)"
set ylabel "largest stable step (s)"
set format x "10^{%L}"
set format y "10^{%L}"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
         using 1:2 with linespoints ls i title word(names, i), \
     for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
         using 1:($4 > 0 && $4 < 1 ? $4 : 1/0) with lines ls i dt 2 notitle
