# Convergence: error against step (or tolerance) per integrator, log-log.
# Variables: dir (one NAME.dat per integrator: param err_x, from
# clothode convergence), names (space-separated), title_text, xlabel_text.
load "plots/common.gp"
set logscale xy
set format xy "10^{%L}"
set xlabel xlabel_text
set ylabel "max particle error (m)"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:2 with linespoints ls i title word(names, i)
