#!/bin/bash
# Why the hang cloth is unpredictable at n = 10 (scripts/hang-sensitivity.sh
# measures that it is).  Two tables, each a title line, a header and rows:
#
#   symmetry  the grid and its pins are symmetric under the mirror
#             z -> 1 - z (j -> n - 1 - j), and so is the exact solution;
#             the largest mirror asymmetry of cvode-bdf's solution at rtol
#             1e-6 and 1e-10 (atol = rtol / 100) at several end times.  It
#             starts at round-off; growth that does not depend on rtol is
#             an unstable antisymmetric mode seeded by round-off.
#   variants  the distance between cvode-bdf's solutions at rtol 1e-6 and
#             1e-10 at T, for the problem as specified and with one
#             parameter changed: ten times the bending stiffness kb, ten
#             times the damping kd, no Type2 (buckling) pairs.
#
# usage: scripts/hang-mechanism.sh symmetry|variants [N [T...]]
#        (default N = 10; T = 0.2 0.3 0.5 1.0 for symmetry, 0.5 for
#        variants; about a minute each).  Runs kept under out/hang-mechanism/.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/clothode
[[ -x $bin ]] || make --no-print-directory "$bin" >&2
table=${1:?usage: hang-mechanism.sh symmetry|variants [N [T...]]}
shift
n=${1:-10}
shift || true
out=out/hang-mechanism/n$n

run() { # dir T rtol [--set ...]
    local dir=$out/$1 T=$2 r=$3
    shift 3
    "$bin" run hang --set cloth.n="$n" --t-end "$T" --rtol "$r" \
        --atol "$(awk -v r="$r" 'BEGIN { print r / 100 }')" --frames 0 \
        --samples 1 --out "$dir" --quiet "$@"
    echo "$dir/final.csv"
}

symmetry() {
    local times=(0.2 0.3 0.5 1.0) T r
    (($#)) && times=("$@")
    printf "hang n = %s, cvode-bdf: mirror asymmetry (m)\n" "$n"
    printf "%-8s" "rtol"
    for T in "${times[@]}"; do printf " %10s" "T=$T"; done
    echo
    for r in 1e-6 1e-10; do
        printf "%-8s" "$r"
        for T in "${times[@]}"; do
            printf " %10s" "$(awk -F, -v size=1 -f scripts/final-asymmetry.awk \
                "$(run "symmetry/T$T/rtol$r" "$T" "$r")")"
        done
        echo
    done
}

variants() {
    local T=${1:-0.5} name
    local -A change=([as-specified]="" [kb*10]=type2.kb=5e-5
                     [kd*10]=damping.kd=1e-2 [no-type2]=type2.enabled=false)
    printf "hang n = %s, T = %s, cvode-bdf: max |x(rtol 1e-6) - x(rtol 1e-10)| (m)\n" "$n" "$T"
    printf "%-14s %10s\n" variant distance
    for name in as-specified 'kb*10' 'kd*10' no-type2; do
        local args=() a b
        [[ -n ${change[$name]} ]] && args=(--set "${change[$name]}")
        a=$(run "variants/$name/rtol1e-6" "$T" 1e-6 "${args[@]}")
        b=$(run "variants/$name/rtol1e-10" "$T" 1e-10 "${args[@]}")
        printf "%-14s %10s\n" "$name" "$(awk -F, -f scripts/final-distance.awk "$a" "$b")"
    done
}

case $table in
symmetry | variants) "$table" "$@" ;;
*) echo "hang-mechanism.sh: unknown table '$table' (symmetry|variants)" >&2; exit 2 ;;
esac
