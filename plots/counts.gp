# Connection counts measured from the topology beside the seed's formulas.
# Variables: data (clothode counts --csv output), title_text.
load "plots/common.gp"
set datafile separator ","
set logscale xy
set xlabel "n (particles per side)"
set ylabel "connections"
set title title_text noenhanced
plot data using 1:2 every ::1 with points ls 1 title "Type1", \
     "" using 1:3 every ::1 with lines ls 1 title "2(n-1)(2n-1)", \
     "" using 1:4 every ::1 with points ls 2 title "Type2", \
     "" using 1:5 every ::1 with lines ls 2 title "4(n-1)(n-2)", \
     "" using 1:6 every ::1 with points ls 3 title "CK", \
     "" using 1:7 every ::1 with lines ls 3 title "8n^2-18n+10"
