#!/usr/bin/env bash
# make paper: LaTeX table bodies from the report's CSV tables
# (results/report, made by scripts/report.sh) into results/report/tex/.
# Every number the paper's tables print comes from these files.
set -euo pipefail
cd "$(dirname "$0")/.."
res=results/report
tex=$res/tex
mkdir -p "$tex"

# Fitted orders per integrator (first row of each in convergence.csv).
awk -F, 'NR > 1 && !($1 in seen) { seen[$1] = 1
         printf "%s & %.2f & %.2f \\\\\n", $1, $12, $13 }' \
    "$res/convergence/convergence.csv" > "$tex/orders.tex"

# Explicit limits: predicted, largest stable, smallest unstable (s).
for p in hang hang-smooth; do
    awk '{ printf "%s & %s & %.4g & %.4g \\\\\n", $1,
                  ($2 == 0 ? "0" : sprintf("%.4g", $2)), $3, $4 }' \
        "$res/limits/$p/limits.txt" > "$tex/limits-$p.tex"
done

# Stability map: n, method, predicted, largest stable, smallest unstable.
awk '{ printf "%d & %s & %.4g & %.4g & %.4g \\\\\n", $1, $2, $3, $4, $5 }' \
    "$res/limits/map/map.txt" > "$tex/map.tex"

# Energy balance per integrator: B(T), max |B|, the energy that moved S
# (the largest of the kinetic energy, |potential - potential(0)| and |W|
# over the samples, as `clothode energy` scales it) and max |B| / S.
awk -F, 'function abs(x) { return x < 0 ? -x : x }
         NR > 1 { if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1; p0[$1] = $4 }
                  b[$1] = $7
                  if (abs($7) > m[$1]) m[$1] = abs($7)
                  if ($3 > sc[$1]) sc[$1] = $3
                  if (abs($4 - p0[$1]) > sc[$1]) sc[$1] = abs($4 - p0[$1])
                  if (abs($6) > sc[$1]) sc[$1] = abs($6) }
         END { for (i = 1; i <= n; i++) { k = order[i]
               printf "%s & %.3e & %.3e & %.3f & %.2g \\\\\n", k, b[k], m[k],
                      sc[k], (sc[k] > 0 ? m[k] / sc[k] : 0) } }' \
    "$res/energy/energy.csv" > "$tex/energy.tex"

# Numerical damping on spring2: the amplitude ratio per step at w h = 1
# and 10, measured and theory, per integrator.
awk -F, 'NR > 1 && $NF == "ok" { k = 0
         if ($2 > 0.999 && $2 < 1.001) k = 1
         if ($2 > 9.99 && $2 < 10.01) k = 10
         if (!k) next
         if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 }
         m[$1, k] = $4; t[$1, k] = $5 }
         # a method without a closed-form theory (the ARKODE DIRK): --
         function th(v, f) { return v ~ /nan/ ? "--" : sprintf(f, v) }
         END { for (i = 1; i <= n; i++) { q = order[i]
               printf "%s & %.6f & %s & %.4g & %s \\\\\n", q, m[q, 1],
                      th(t[q, 1], "%.6f"), m[q, 10], th(t[q, 10], "%.4g") } }' \
    "$res/damping/damping.csv" > "$tex/damping.tex"
# ... and the energy left per mode of hang-smooth, mean over the slowest,
# middle and fastest third of the modes.
awk -F, 'NR > 1 && $NF == "ok" { if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 }
         c[$1]++; r[$1, c[$1]] = $5 }
         END { for (i = 1; i <= n; i++) { q = order[i]; line = q
               for (j = 0; j < 3; j++) { a = int(c[q] * j / 3) + 1; b = int(c[q] * (j + 1) / 3)
                   s = 0; for (k = a; k <= b; k++) s += r[q, k]
                   line = line sprintf(" & %.3g", s / (b - a + 1)) }
               print line " \\\\" } }' \
    "$res/damping/damping-modes.csv" > "$tex/damping-modes.tex"
# ... and of the prestressed hanging cloth: the in-plane and the
# out-of-plane (normal fraction > 1/2) modes, each by thirds.
awk -F, 'NR > 1 && $NF == "ok" { if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 }
         g = $7 > 0.5; c[$1, g]++; r[$1, g, c[$1, g]] = $5 }
         END { for (i = 1; i <= n; i++) { q = order[i]; line = q
               for (g = 0; g < 2; g++) for (j = 0; j < 3; j++) {
                   a = int(c[q, g] * j / 3) + 1; b = int(c[q, g] * (j + 1) / 3)
                   s = 0; for (k = a; k <= b; k++) s += r[q, g, k]
                   line = line sprintf(" & %.3g", s / (b - a + 1)) }
               print line " \\\\" } }' \
    "$res/damping/hanging/damping-modes.csv" > "$tex/damping-wrinkles.tex"

# Work-precision: every level that ran, error and CPU time.
awk -F, 'NR > 1 && $NF == "ok" {
         printf "%s & %s & %.3g & %.3e & %.3f & %d \\\\\n",
                ($1 == last ? "" : $1), $2, $3, $4, $11, $9; last = $1 }' \
    "$res/workprecision/workprecision.csv" > "$tex/workprecision.tex"

# Wrinkles of compress, forming (wrinkles) and formed (kept): method,
# step, time reached, amplitude, count.
for t in wrinkles kept; do
    awk '{ split($2, kv, "="); printf "%s & %s %s & %s & %.4f & %d & %s \\\\\n",
           $1, kv[1], kv[2], $3, $4, $5, $6 }' \
        "$res/wrinkles/$t.txt" > "$tex/$t.tex"
done

# Predictability of hang: tables of rtol rows, one column per T (the
# sensitivity and the mirror asymmetry), and the parameter variants.
for t in sensitivity symmetry; do
    awk 'NR > 2 && NF > 1 { line = $1; for (i = 2; i <= NF; i++) line = line " & " $i
                             print line " \\\\" }' \
        "$res/$t.txt" > "$tex/$t.tex"
    awk 'NR == 2 { for (i = 2; i <= NF; i++) printf "%s%s", (i > 2 ? " & " : ""), $i }' \
        "$res/$t.txt" > "$tex/$t-head.tex"
done
awk 'NR > 2 { name = $1; sub(/^as-specified$/, "as specified", name)
              sub(/^kb\*10$/, "$10\\,k_b$", name); sub(/^kd\*10$/, "$10\\,k_d$", name)
              sub(/^no-type2$/, "no Type2 pairs", name)
              printf "%s & %s \\\\\n", name, $2 }' \
    "$res/variants.txt" > "$tex/variants.tex"
# Contact on drape-sphere: method, step, worst penetration (mm), when (s),
# steps, CPU time (s), how the run ended.
awk '{ end = $7; sub(/^failed@/, "stopped at ", end); sub(/^ok$/, "ran", end)
       printf "%s & %s & %.3g & %s & %d & %.2f & %s \\\\\n",
              $1, $2, 1000 * $3, $4, $5, $6, end }' \
    "$res/contact/drape.txt" > "$tex/drape.tex"
# The claims of the sources (results/report/claims/claims.csv, every field
# quoted, made by scripts/claims.sh; run here if a report made before it
# lacks it): claims.tex (id, source and section, claim, value, verdict),
# claims-how.tex (id, configuration, quantity, command) and
# The contact study: jiao-sphere's runs (response, step, stable, worst
# penetration in m, largest stretch, CPU) and tunnel's speeds (speed, then
# contacts at T and worst penetration in mm for projection and penalty).
cs=$res/contact-study
awk -F, 'NR > 1 { printf "%s & %s & %s & %.3g & %.3g & %.2f \\\\\n", ($2 == last ? "" : $2), $3,
                  ($5 == 1 ? "stable" : "unstable"), $7, $11, $13; last = $2 }' \
    "$cs/jiao-sphere/contact.csv" > "$tex/contact-study.tex"
paste "$cs/tunnel-project.dat" "$cs/tunnel-penalty.dat" |
    awk '{ printf "%g & %d & %.3g & %d & %.3g \\\\\n", $1, $3, 1000 * $2, $6, 1000 * $5 }' \
    > "$tex/tunnel.tex"

# claims-values.tex, every row's value as \cv{ID} for the text.
[ -f "$res/claims/claims.csv" ] || scripts/claims.sh build/clothode "$res/claims"
awk '
function tex(s) {
    gsub(/\\/, "\\textbackslash{}", s); gsub(/_/, "\\_", s); gsub(/%/, "\\%", s)
    gsub(/&/, "\\\\&", s); gsub(/#/, "\\#", s); gsub(/\^/, "\\^{}", s)
    gsub(/~/, "\\~{}", s); gsub(/\$/, "\\$", s)
    return s
}
# a number as LaTeX: 3 significant digits, powers of ten for small or large
function num(v,   t, m) {
    if (v !~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/) return tex(v)
    t = sprintf("%.3g", v)
    if (v != 0 && (v + 0 < 1e-2 && v + 0 > -1e-2 || v + 0 >= 1e5)) {
        t = sprintf("%.2e", v); split(t, m, "e")
        return sprintf("$%g\\cdot10^{%d}$", m[1], m[2])
    }
    return t
}
NR == 1 { next }
{   line = substr($0, 2, length($0) - 2); n = split(line, f, "\",\"")
    id = tex(f[1]); gsub(/-/, "-\\allowbreak{}", id); unit = (f[8] == "" ? "" : "\\," tex(f[8]))
    printf "\\texttt{%s} & %s, %s & %s & %s%s & %s \\\\\n", id, tex(f[2]), tex(f[3]),
           tex(f[4]), num(f[7]), unit, tex(f[9]) > (dir "/claims.tex")
    cmd = tex(f[10]); gsub(/-/, "-{}", cmd)  # no -- ligature in the options
    printf "\\texttt{%s} & %s & %s & \\texttt{%s} \\\\\n", id, tex(f[5]), tex(f[6]),
           cmd > (dir "/claims-how.tex")
    printf "\\expandafter\\def\\csname cv:%s\\endcsname{%s}\n", f[1], num(f[7]) > (dir "/claims-values.tex")
}' dir="$tex" "$res/claims/claims.csv"
echo "paper: tables in $tex"
