# Max over particles of |x_a - x_b| between two final.csv files
# (p,x,y,z,...), printed as %.2e.
# usage: awk -F, -f scripts/final-distance.awk A/final.csv B/final.csv
NR == FNR { if (FNR > 1) { x[FNR] = $2; y[FNR] = $3; z[FNR] = $4 }; next }
FNR > 1 {
    d = sqrt(($2 - x[FNR])^2 + ($3 - y[FNR])^2 + ($4 - z[FNR])^2)
    if (d > m) m = d
}
END { printf "%.2e", m }
