# The Verlet-and-PBD report's robustness rule on verlet-drop at 1/60 s.
# Left: the report's own parameters K (elastic) and U (damping) at 8
# constraint iterations, where the rule "explodes if K and U are over 13
# and iterations over 5" applies, its region shaded.
# Right: every cell of the map at the stiffness k = iterations x K and the
# damping kd = iterations x U the Verlet step sees.
# The line k/k0 + kd/d0 = 1 that scripts/claims.sh fits to the cells.
# Variables: dir (stable.dat and blowup.dat: K U iterations k kd), k0, d0,
# title_text.
load "plots/common.gp"
if (term eq "pdf") {
    set terminal pdfcairo size 7in,3.4in enhanced font "Sans,9"
} else {
    set terminal pngcairo size 1100,520 enhanced font "Sans,11"
}
set output outfile
set multiplot layout 1,2 title title_text noenhanced
set logscale xy
set key outside below horizontal
set xlabel "K"
set ylabel "U"
set title "8 constraint iterations (past the rule's 5)"
set object 1 rect from 13,13 to 25,25 fc rgb "#e08080" fs solid 0.4 noborder behind
set label 1 "rule: explodes" at 13.5,9 font ",8"
set xrange [1.5:25]
set xtics (2, 5, 8, 10, 13, 15, 20)
set yrange [0.007:25]
plot sprintf("%s/stable.dat", dir) using ($3 == 8 ? $1 : 1/0):2 with points ls 3 pt 6 ps 1.5 title "bounded", \
     sprintf("%s/blowup.dat", dir) using ($3 == 8 ? $1 : 1/0):2 with points ls 2 pt 2 ps 1.5 title "blew up"
unset object 1
unset label 1
set xlabel "k = iterations x K (N/m)"
set ylabel "kd = iterations x U (N s/m)"
set title "every cell (1, 3, 5, 8, 10 iterations)"
set xrange [1.5:250]
set xtics auto
set yrange [0.007:250]
set samples 400
line(k) = k < k0 ? d0 * (1 - k / k0) : 1/0
plot sprintf("%s/stable.dat", dir) using 4:5 with points ls 3 pt 6 ps 1.5 title "bounded", \
     sprintf("%s/blowup.dat", dir) using 4:5 with points ls 2 pt 2 ps 1.5 title "blew up", \
     line(x) with lines ls 1 title sprintf("k/%.3g + kd/%.3g = 1", k0, d0)
unset multiplot
