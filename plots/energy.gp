# Energy balance B(t) = E(t) - E(0) - W(t) per integrator.
# Variables: dir (NAME.dat: t balance), names, title_text.
load "plots/common.gp"
set xlabel "t (s)"
set ylabel "energy made (+) or destroyed (-) (J)"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:2 with lines ls i title word(names, i)
