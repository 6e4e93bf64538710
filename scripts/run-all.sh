#!/usr/bin/env bash
# Run every registered integrator on a problem for a short time at a step it
# can take (explicit and adaptive-explicit: dt 1e-5; implicit: dt 1e-3;
# adaptive: the problem's tolerances) and print one line of statistics each.
# usage: scripts/run-all.sh [clothode] [problem] [t_end] [extra run options]
set -uo pipefail
bin=${1:-build/clothode}
problem=${2:-hang}
t_end=${3:-0.2}
shift 3 2>/dev/null || shift $#
out=${OUT:-out/run-all}
printf "%-20s %6s %8s %9s %8s %8s %9s %9s %s\n" integrator status steps \
    rhs jac setups newton cpu_s "max d/L"
status=0
while read -r name _; do
    case $name in
        fe|symplectic-euler|symplectic-euler-x|verlet|velocity-verlet|rk4)
            step=(--dt 1e-5) ;;
        verlet-pbd) step=(--dt 1e-5 --set pbd.enabled=true) ;;
        kinsol-*|semi-*) step=(--dt 1e-3) ;;
        *) step=() ;;
    esac
    dir="$out/$name"
    if "$bin" run "$problem" --integrator "$name" "${step[@]}" \
            --t-end "$t_end" --frames 0 --samples 20 --out "$dir" --quiet \
            "$@" 2>"$dir.err"; then
        ok=ok
    else
        ok=FAIL
        status=1
    fi
    stat() { awk -F, -v k="$1" '$1 == k { print $2 }' "$dir/stats.csv" 2>/dev/null; }
    stretch=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "max_stretch") c = i }
        END { if (c) print $c }' "$dir/series.csv" 2>/dev/null)
    printf "%-20s %6s %8s %9s %8s %8s %9s %9.3f %s\n" "$name" "$ok" \
        "$(stat steps)" "$(stat rhs_evals)" "$(stat jac_evals)" \
        "$(stat lin_setups)" "$(stat nonlin_iters)" "$(stat cpu)" \
        "${stretch:-nan}"
    [[ $ok == ok ]] || sed 's/^/    /' "$dir.err"
done < <("$bin" list | sed -n '/^integrators:/,/^force terms:/p' | sed '1d;$d')
exit $status
