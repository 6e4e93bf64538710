# First-order eigenvalues of the linearised cloth in the complex plane.
# Variables: data (spectrum.csv), title_text.
load "plots/common.gp"
set datafile separator ","
set xlabel "Re lambda (1/s)"
set ylabel "Im lambda (1/s)"
set title title_text noenhanced
plot data using ((strcol(1) eq "lambda") ? $3 : NaN):4 with points ls 1 \
     pt 7 ps 0.5 title "lambda"
