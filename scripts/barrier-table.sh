#!/bin/sh
# The barrier's acceptance runs (docs/model.md, contact, barrier): on
# drape-sphere-barrier and drape-box-barrier, semi-be, semi-bdf2,
# kinsol-be and kinsol-bdf2 at dt = 0.01, 0.02, 0.04, each to the
# problem's t_end; one Markdown table row per run with the least signed
# distance of a free particle to a barrier obstacle over every step, the
# Newton iterations (0 for the one-solve semi-implicit methods) and the
# exit status.
# Usage: scripts/barrier-table.sh [CLOTHODE] [OUTDIR]
set -u
bin=${1:-build/clothode}
out=${2:-/tmp/clothode-barrier-table}
mkdir -p "$out"
echo "| problem | integrator | dt (s) | min distance (m) | Newton iterations | steps | exit |"
echo "|---|---|---|---|---|---|---|"
for p in drape-sphere-barrier drape-box-barrier; do
    for i in semi-be semi-bdf2 kinsol-be kinsol-bdf2; do
        for dt in 0.01 0.02 0.04; do
            log="$out/$p-$i-$dt.txt"
            "$bin" run "problems/$p.ini" --integrator "$i" --dt "$dt" \
                --frames 0 --out "$out/$p-$i-$dt" >"$log" 2>&1
            rc=$?
            d=$(sed -n 's/^barrier *min distance \([^ ]*\) m.*/\1/p' "$log")
            it=$(sed -n 's/^ *nonlinear iterations *//p' "$log")
            st=$(sed -n 's/^ *steps *//p' "$log")
            echo "| $p | $i | $dt | $d | $it | $st | $rc |"
        done
    done
done
