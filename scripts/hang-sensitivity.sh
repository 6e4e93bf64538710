#!/bin/bash
# The predictability horizon of the hang cloth: cvode-bdf at rtol 1e-6 ..
# 1e-10 (atol = rtol / 100) against a reference at rtol 1e-11, max over
# particles of the distance between final positions, at several end times.
# An error proportional to rtol means the tolerance controls the answer;
# one that stays put as rtol falls means the problem forgets its initial
# state faster than the tolerance can follow.
#
# usage: scripts/hang-sensitivity.sh [N [T...]]   (default N = 10,
#        T = 0.2 0.3 0.5 1.0; about 10 CPU minutes in all)
# Table on stdout; the runs are kept under out/hang-sensitivity/.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/clothode
[[ -x $bin ]] || make --no-print-directory "$bin" >&2
n=${1:-10}
shift || true
times=(0.2 0.3 0.5 1.0)
(($#)) && times=("$@")
rtols=(1e-6 1e-7 1e-8 1e-9 1e-10)
out=out/hang-sensitivity/n$n

run() { # T rtol
    local dir=$out/T$1/rtol$2
    "$bin" run hang --set cloth.n="$n" --t-end "$1" --rtol "$2" \
        --atol "$(awk -v r="$2" 'BEGIN { print r / 100 }')" --frames 0 \
        --samples 1 --out "$dir" --quiet
    echo "$dir/final.csv"
}

printf "hang n = %s, cvode-bdf: max |x - x_ref| (m), reference rtol 1e-11\n" "$n"
printf "%-8s" "rtol"
for T in "${times[@]}"; do printf " %10s" "T=$T"; done
echo
declare -A ref
for T in "${times[@]}"; do ref[$T]=$(run "$T" 1e-11); done
for r in "${rtols[@]}"; do
    printf "%-8s" "$r"
    for T in "${times[@]}"; do
        printf " %10s" "$(awk -F, -f scripts/final-distance.awk "${ref[$T]}" \
            "$(run "$T" "$r")")"
    done
    echo
done
