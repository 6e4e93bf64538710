# The inverse sinc of the Type2 curvature beside the seed's polynomial.
# Variables: data (clothode asinc --csv output), title_text.
load "plots/common.gp"
set datafile separator ","
set xlabel "y = d/L"
set ylabel "t = kappa L / 2"
set y2label "p(y) - asinc(y)/pi"
set y2tics
set ytics nomirror
set title title_text noenhanced
plot data using 1:2 every ::1 with lines ls 1 title "asinc(y)", \
     "" using 1:3 every ::1 with lines ls 3 title "asinc(y)/pi", \
     "" using 1:4 every ::1 with lines ls 2 dt 2 title "seed p(y)", \
     "" using 1:($4 - $3) every ::1 axes x1y2 with lines ls 4 \
        title "p - asinc/pi (right)"
