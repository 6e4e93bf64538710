# A frame of a contact scene: the cloth (an OBJ frame) over its obstacles
# (the obstacles OBJ written beside it), as shaded triangles seen from
# above and aside.  Variables: term (png or pdf), outfile, cloth, obstacles
# (OBJ files), title_text.
load "plots/common.gp"
set title title_text noenhanced
unset key
set xlabel "x (m)"
set ylabel "z (m)"
set zlabel "y (m)" rotate by 90
set view 62, 30, 1.5, 1
set view equal xyz
set xyplane 0
set pm3d depthorder border lc rgb "#404040" lw 0.3
unset colorbox
# One block of three vertices (x, z, y) and a blank line per triangle.
tris(f) = sprintf("< awk '$1 == \"v\" { x[++n] = $2; y[n] = $3; z[n] = $4 } $1 == \"f\" { for (i = 2; i <= 4; i++) { split($i, a, \"/\"); print x[a[1]], z[a[1]], y[a[1]] } print \"\" }' %s", f)
splot tris(obstacles) with polygons fillstyle solid 0.9 fc rgb "#c8c8c8", \
      tris(cloth) with polygons fillstyle solid 1.0 fc rgb "#3b6fb6"
