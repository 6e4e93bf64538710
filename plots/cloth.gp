# Draw a cloth state (a final.csv or state file: p,x,y,z,vx,vy,vz) as a
# shaded surface with its pinned particles marked.
# Variables: final (input), outfile (PNG), nv (particles per grid row),
#            pins (space-separated particle indices).
if (!exists("nv")) nv = 16
if (!exists("pins")) pins = "0 15"
set terminal pngcairo size 900,700 enhanced font "Sans,11"
set output outfile
set datafile separator ","
set title "clothode: final state of ".final noenhanced
set xlabel "x (m)"
set ylabel "z (m)"
set zlabel "y (m)" rotate by 90
set view 60, 35, 1, 1
set view equal xy
set pm3d depthorder border lc rgb "#303030" lw 0.5
set palette defined (0 "#1f3b73", 0.5 "#4f9fd0", 1 "#e8f4ff")
set style fill solid 1.0
unset colorbox
set key top left
# Blank line after every grid row, so splot sees a surface.
grid = sprintf("< awk -F, 'NR > 1 { print; if ((NR - 1) %% %d == 0) print \"\" }' %s", nv, final)
pinned = sprintf("< awk -F, 'BEGIN { split(\"%s\", q, \" \"); for (k in q) keep[q[k]] = 1 } NR > 1 && ($1 in keep)' %s", pins, final)
splot grid using 2:4:3 with pm3d title "cloth", \
      pinned using 2:4:3 with points pt 7 ps 2 lc rgb "#d62728" title "pins"
