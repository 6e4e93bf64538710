#!/usr/bin/env bash
# The measurements behind paper/findings.md, "Baraff-Witkin constraints
# and continuous detection" (docs/model.md 4.7, 4.8):
#  1. drape-sphere (3 s) and drape-box (2 s) with both obstacles answering
#     `response = constraint` (their friction kept, the penalty keys
#     dropped), semi-be and semi-bdf2 at dt = 0.01, 0.02, 0.04 (and
#     pcg at 0.01): the worst penetration over the run (seen after every
#     step) and when, the penetration at the end (the series' last
#     max_penetration), linear solves per step, CPU (or the failure);
#  2. verlet-scene1 (its sphere driven 6 m along x through the hanging
#     cloth from t = 1.5 s) with a small fast sphere, radius 0.2 m in
#     0.1 s (60 m/s: 1 m a step of 1/60 s, more than its diameter with the
#     offset, 0.5 m), the same sphere at 3 m/s, and the scene's own 0.8 m
#     sphere at 3 m/s, with ccd off and on, to t = 2.5 s: the largest
#     contact force at an output (the projection impulses of a step over
#     the step), the largest kinetic energy after t = 1.5 s, the cloth's
#     largest x at the end.
# usage: scripts/constraint-ccd.sh [CLOTHODE] [OUTDIR]   (about 2 minutes)
set -euo pipefail
bin=${1:-build/clothode}
out=${2:-out/constraint-ccd}
cd "$(dirname "$0")/.."
mkdir -p "$out"

# The constraint variant of a drape problem: every obstacle's response.
constrained() {
    awk '/^\[obstacle\./ { o = 1; print; next } /^\[/ { o = 0 }
         o && /^(k|eps|damping|v_smooth) *=/ { next }
         o && /^response/ { print "response = constraint"; next }
         { print }' "problems/$1.ini" > "$out/$1-constraint.ini"
}

echo "problem integrator dt linsol worst_pen_m at_s end_pen_m solves_per_step cpu_s"
for p in drape-sphere drape-box; do
    constrained "$p"
    T=3; [[ $p == drape-box ]] && T=2
    for i in semi-be semi-bdf2; do
        for run in "0.01 klu" "0.02 klu" "0.04 klu" "0.01 pcg"; do
            set -- $run
            dir="$out/$p-$i-$1-$2"
            if ! summary=$("$bin" run "$out/$p-constraint.ini" \
                    --integrator "$i" --dt "$1" --linsol "$2" --t-end "$T" \
                    --frames 0 --format csv --out "$dir" 2>&1); then
                echo "$p $i $1 $2 failed: $(grep -m1 '^clothode: ' <<<"$summary" | cut -c11-)"
                continue
            fi
            pen=$(sed -n 's/.*worst penetration \([^ ]*\) m at t = \([^ ]*\) s/\1 \2/p' <<<"$summary")
            solves=$(sed -n 's/^  linear solves *//p' <<<"$summary")
            steps=$(sed -n 's/^  steps *//p' <<<"$summary")
            cpu=$(sed -n 's/^  cpu time \[s\] *//p' <<<"$summary")
            endpen=$(awk -F, 'NR == 1 { for (k = 1; k <= NF; k++)
                                          if ($k == "max_penetration") c = k }
                              END { print $c }' "$dir/series.csv")
            echo "$p $i $1 $2 $pen $endpen $(awk "BEGIN { printf \"%.2f\", $solves / $steps }") $cpu"
        done
    done
done

echo
echo "sphere radius_m speed_m_s ccd max_contact_force_N max_kinetic_J cloth_max_x_m"
for run in "0.2 60 1.6" "0.2 3 3.5" "0.8 3 3.5"; do
    set -- $run
    for ccd in false true; do
        dir="$out/scene1-$1-$ccd"
        "$bin" run verlet-scene1 --t-end 2.5 --frames 0 --format csv \
            --set obstacle.ball.radius="$1" \
            --set "obstacle.ball.path=0: 0, 0, 0; 1.5: 0, 0, 0; $3: 6, 0, 0" \
            --set obstacle.ball.ccd="$ccd" --out "$dir" --quiet
        maxx=$(awk -F, 'NR > 1 && (m == "" || $2 > m) { m = $2 } END { printf "%.3f", m }' "$dir/final.csv")
        peaks=$(awk -F, 'NR == 1 { for (k = 1; k <= NF; k++) {
                                     if ($k == "contact_force") f = k
                                     if ($k == "kinetic") e = k }; next }
                          $f > mf { mf = $f }
                          $1 >= 1.5 && $e > me { me = $e }
                          END { printf "%.4g %.4g", mf, me }' "$dir/series.csv")
        echo "ball $1 $2 $ccd $peaks $maxx"
    done
done
