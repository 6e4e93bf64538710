# Shared set-up of the report figures: terminal from `term` (png or pdf)
# and output file `outfile`, CSV-free whitespace data, a muted palette.
if (!exists("term")) term = "png"
if (term eq "pdf") {
    set terminal pdfcairo size 6in,4.2in enhanced font "Sans,9"
} else {
    set terminal pngcairo size 900,630 enhanced font "Sans,11"
}
set output outfile
set key outside right top noenhanced
set grid lc rgb "#d0d0d0"
set style line 1 lc rgb "#1f77b4" lw 2 pt 7
set style line 2 lc rgb "#d62728" lw 2 pt 5
set style line 3 lc rgb "#2ca02c" lw 2 pt 9
set style line 4 lc rgb "#9467bd" lw 2 pt 11
set style line 5 lc rgb "#ff7f0e" lw 2 pt 13
set style line 6 lc rgb "#8c564b" lw 2 pt 3
set style line 7 lc rgb "#e377c2" lw 2 pt 4
set style line 8 lc rgb "#7f7f7f" lw 2 pt 6
set style line 9 lc rgb "#bcbd22" lw 2 pt 8
set style line 10 lc rgb "#17becf" lw 2 pt 10
set style line 11 lc rgb "#393b79" lw 2 pt 12
set style line 12 lc rgb "#637939" lw 2 pt 14
set style increment user
