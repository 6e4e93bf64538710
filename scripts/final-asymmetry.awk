# Mirror asymmetry of a hang cloth in a final.csv: the hang grid (particle
# p = i n + j at (i h, 0, j h), pins at j = 0 and j = n - 1) is symmetric
# under z -> size - z, j -> n - 1 - j; printed is the max over particles of
# |x(i, j) - mirror(x(i, n - 1 - j))|, as %.2e.
# usage: awk -F, -v size=1 -f scripts/final-asymmetry.awk final.csv
FNR > 1 { x[$1] = $2; y[$1] = $3; z[$1] = $4; count++ }
END {
    n = int(sqrt(count) + 0.5)
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            a = i * n + j; b = i * n + n - 1 - j
            d = sqrt((x[a] - x[b])^2 + (y[a] - y[b])^2 + (z[a] + z[b] - size)^2)
            if (d > m) m = d
        }
    printf "%.2e", m
}
