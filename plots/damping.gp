# Numerical damping: the amplitude ratio per step against w h per
# integrator, measured (points) and the theory |R(i w h)| (lines).
# Variables: dir (NAME.dat: wh measured theory, from clothode damping),
# names, title_text.
load "plots/common.gp"
set logscale xy
set format xy "10^{%L}"
set yrange [1e-3:2]
set xlabel "w h"
set ylabel "amplitude ratio per step"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:2 with points ls i title word(names, i), \
     for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:3 with lines ls i notitle
