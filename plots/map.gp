# Stability map: the explicit step limit against the grid size, measured
# (points) and predicted by the spectrum (dashed), per method.
# Variables: dir (NAME.dat: n predicted measured), names, title_text.
load "plots/common.gp"
set logscale xy
set xlabel "n (particles per side)"
set ylabel "largest stable step (s)"
set xtics (6, 8, 12, 16)
set xrange [5:18]
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
         using 1:3 with linespoints ls i title word(names, i)." (measured)", \
     for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
         using 1:2 with lines ls i dt 2 title word(names, i)." (predicted)"
