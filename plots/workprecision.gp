# Work-precision: CPU time against the error reached, log-log.
# Variables: dir (NAME.dat: err_x cpu), names, title_text, note_text
# (optional).
load "plots/common.gp"
set logscale xy
set format xy "10^{%L}"
set xlabel "max particle error (m)"
set ylabel "CPU time (s)"
set title title_text noenhanced
# note_text (optional): the methods without a point, and why.
if (exists("note_text")) {
    set bmargin 6
    set label 1 note_text at screen 0.01, 0.065 left font ",8" noenhanced
}
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:2 with linespoints ls i title word(names, i)
