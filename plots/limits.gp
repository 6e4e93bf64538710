# Explicit step limits: the largest stable step measured by
# clothode stability against the spectral prediction, per integrator.
# Variables: data (integrator predicted stable unstable, one row each,
# whitespace-separated), title_text.
load "plots/common.gp"
set style data histogram
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set logscale y
set format y "10^{%L}"
set ylabel "step (s)"
set xtics rotate by -30 noenhanced
set title title_text noenhanced
plot data using 2:xtic(1) ls 1 title "predicted (spectrum)", \
     "" using 3 ls 2 title "largest stable (measured)"
