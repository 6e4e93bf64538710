# The contact study (clothode contact): left, jiao-sphere with semi-bdf2,
# the largest stretch d/L over each run against dt per response (open
# points: the run was unstable, d/L > 3); right, tunnel with semi-be at
# dt = 1e-3 s, the particles in contact with the sphere at T against its
# speed (0: it went through).  Variables: dir (project.dat, penalty.dat:
# dt worst_penetration_m max_stretch stable; tunnel-RESPONSE.dat: speed
# worst_penetration_m contacts), title_text.
load "plots/common.gp"
set multiplot layout 1, 2 title title_text noenhanced
set logscale x
set key inside left bottom
set yrange [1:3.5]
set xlabel "dt (s)"
set ylabel "largest stretch d/L"
set title "jiao-sphere, semi-bdf2" noenhanced
plot for [i = 1:2] sprintf("%s/%s.dat", dir, word("project penalty", i)) \
         using 1:($4 == 1 ? $3 : 1/0) with linespoints ls i title word("project penalty", i), \
     for [i = 1:2] sprintf("%s/%s.dat", dir, word("project penalty", i)) \
         using 1:($4 == 0 ? $3 : 1/0) with points ls i pt 6 ps 1.5 notitle, \
     3 with lines lc rgb "#7f7f7f" dt 2 title "instability threshold"
set xlabel "sphere speed (m/s)"
set ylabel "particles in contact at T"
set title "tunnel, semi-be, dt = 1e-3 s, r = 0.2 m" noenhanced
set key inside left bottom
set autoscale y
plot for [i = 1:2] sprintf("%s/tunnel-%s.dat", dir, word("project penalty", i)) \
         using 1:3 with linespoints ls i title word("project penalty", i)
unset multiplot
