#!/usr/bin/env bash
# Cross-check of two unrelated integrators on the default problem:
# CVODE BDF (rtol 1e-8, atol 1e-10) against symplectic Euler (dt 2e-5) on
# hang, T = 0.5 s; prints the largest distance between their final
# positions.  (A smaller version runs in the test suite: tests/test_cli.c.)
# usage: scripts/compare-hang.sh [path/to/clothode] [extra run options]
set -euo pipefail
bin=${1:-build/clothode}
shift || true
out=${OUT:-out/compare-hang}
"$bin" run problems/hang.ini --integrator cvode-bdf --rtol 1e-8 --atol 1e-10 \
    --t-end 0.5 --frames 0 --out "$out/cvode" --quiet "$@"
"$bin" run problems/hang.ini --integrator symplectic-euler --dt 2e-5 \
    --t-end 0.5 --frames 0 --out "$out/symplectic" --quiet "$@"
paste -d, "$out/cvode/final.csv" "$out/symplectic/final.csv" | awk -F, '
    NR > 1 {
        d = 0
        for (i = 2; i <= 4; i++) { e = $i - $(i + 7); d += e * e }
        d = sqrt(d)
        if (d > m) { m = d; p = $1 }
    }
    END {
        printf "max |x_cvode - x_symplectic| = %.3e m (particle %d)\n", m, p
        if (m >= 1e-3) { print "FAIL: not below 1e-3 m"; exit 1 }
        print "ok: below 1e-3 m"
    }'
