# Work-precision: CPU time against the error reached, log-log.
# Variables: dir (NAME.dat: err_x cpu), names, title_text.
load "plots/common.gp"
set logscale xy
set format xy "10^{%L}"
set xlabel "max particle error (m)"
set ylabel "CPU time (s)"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:2 with linespoints ls i title word(names, i)
