# Contact at several steps: the deepest penetration into an obstacle
# against time, per run.  Variables: dir (NAME.dat: t penetration_m),
# names, title_text.
load "plots/common.gp"
set xlabel "t (s)"
set ylabel "max penetration (mm)"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:($2 * 1000) with lines ls i title word(names, i)
