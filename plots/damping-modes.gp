# Energy left in each eigenmode of a cloth after T against w dt per
# integrator, measured (points) and amplification(w dt)^(2 T/dt) (lines).
# Variables: dir (NAME.dat: wh ratio theory, from clothode damping
# --modes), names, title_text.
load "plots/common.gp"
set logscale xy
set format xy "10^{%L}"
set yrange [1e-20:10]
set xlabel "w dt"
set ylabel "E(T) / E(0) per mode"
set title title_text noenhanced
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:2 with points ls i ps 0.5 title word(names, i), \
     for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 1:3 with lines ls i notitle
