# Equal-budget study (clothode budget): left, the hanging chain of hard
# constraints (xpbd, budget B per step split as S substeps x B/S
# iterations): largest stretch and energy lost against S; right, the
# springs of ms-hang: final error against CPU time for every method, its
# splits joined in order of S.  Variables: chain (file "S stretch energy"),
# dir (one NAME.dat per method: "S err_x cpu"), names, title_text.
load "plots/common.gp"
if (term eq "pdf") { set terminal pdfcairo size 9in,3.6in enhanced font "Sans,9" } \
else { set terminal pngcairo size 1350,540 enhanced font "Sans,11" }
set output outfile
set multiplot layout 1,2 title title_text noenhanced
set logscale xy
set format y "10^{%L}"
set key inside top right
set xlabel "substeps S (iterations K = B / S)"
set ylabel "largest stretch d/L - 1;  energy lost (J)"
set title "xpbd-chain: 20 hard links, B = 20, dt = 0.01 s, T = 1 s"
plot chain using 1:2 with linespoints ls 1 title "stretch", \
     chain using 1:(-$3) with linespoints ls 2 title "-(E(T) - E(0))"
set format x "10^{%L}"
set xlabel "CPU time (s)"
set ylabel "max particle error at T (m)"
set title "ms-hang springs, B = 8, dt = 0.01 s, T = 0.5 s (points: S = 1, 2, 4, 8)"
set key outside right top
plot for [i = 1:words(names)] sprintf("%s/%s.dat", dir, word(names, i)) \
     using 3:2 with linespoints ls i title word(names, i)
unset multiplot
