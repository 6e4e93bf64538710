# Buckling of the compressed strip: the largest out-of-plane displacement
# against time, per run.  Variables: dir (NAME.dat: t amplitude), names,
# title_text.
load "plots/common.gp"
set xlabel "t (s)"
set ylabel "max out-of-plane displacement (m)"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:2 with lines ls i title word(names, i)
