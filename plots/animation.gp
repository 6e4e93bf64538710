# Animated GIF of a run's OBJ frames (frame_00000.obj ..): the cloth as a
# shaded surface, fixed axes so that the motion shows.
# Variables: dir (the run's output directory), nframes (frames after the
# first), nv (particles per grid row), outfile, and the axis ranges
# xr0 xr1 yr0 yr1 zr0 zr1 (x, z, y of the model).
set terminal gif animate delay 12 size 640,480 optimize
set output outfile
set xlabel "x (m)"
set ylabel "z (m)"
set zlabel "y (m)" rotate by 90
set xrange [xr0:xr1]
set yrange [zr0:zr1]
set zrange [yr0:yr1]
set cbrange [yr0:yr1]
set view 60, 35, 1, 1
set pm3d depthorder border lc rgb "#303030" lw 0.5
set palette defined (0 "#1f3b73", 0.5 "#4f9fd0", 1 "#e8f4ff")
unset colorbox
unset key
do for [i = 0:nframes] {
    file = sprintf("%s/frame_%05d.obj", dir, i)
    set title sprintf("frame %d of %d", i, nframes)
    # vertices in particle order; a blank line after every grid row
    grid = sprintf("< awk '$1 == \"v\" { print $2, $3, $4; if (++k %% %d == 0) print \"\" }' %s", nv, file)
    splot grid using 1:3:2 with pm3d
}
