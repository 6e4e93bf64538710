#!/usr/bin/env bash
# Check that two builds of clothode write byte-identical outputs
# (docs/architecture.md, "Checking that outputs stay byte-identical"): the
# same `clothode run`s with OLD_BIN into OUTDIR/old and with NEW_BIN into
# OUTDIR/new, then every output file compared with cmp; stats.csv without
# its timing rows (wall, cpu; older builds wrote them), run.json not at all
# (a newer build's provenance: times, paths, the build), and each run's
# exit status and messages (OUTDIR/*/NAME.log) too.  The runs:
#   problem/P      every problem of problems/ at a shortened t_end
#                  (T_END, default 0.5 s) with its own integrator
#   demo           the run of `make demo` (scripts/demo.sh)
#   integrator/I   every integrator of OLD_BIN on an 8 x 8 hang to 0.05 s
#                  (explicit: dt 1e-5; implicit fixed-step: dt 1e-3)
#   linsol/L       semi-bdf2 and cvode-bdf with every linear solver
#   test/...       runs the test suite makes through the command line
#                  (tests/test_cli.c, test_tearing.c, test_verlet_pbd.c),
#                  a blow-up that stops with an error among them
# Prints one line per run, `NAME: identical` or `NAME: differs: FILE...`
# (NAME.log: the exit status or messages), and exits 1 if any run
# differs.  82 runs: about 2.5 minutes on two lightly loaded cores.
# usage: scripts/compare-outputs.sh OLD_BIN NEW_BIN [OUTDIR]
set -uo pipefail
if [[ $# -lt 2 || $# -gt 3 ]]; then
    echo "usage: scripts/compare-outputs.sh OLD_BIN NEW_BIN [OUTDIR]" >&2
    exit 2
fi
old=$1 new=$2 outdir=${3:-out/compare}
t_end=${T_END:-0.5}
cd "$(dirname "$0")/.." || exit 2

# One line per run: its name, then the arguments of `clothode run`.
runs() {
    local p name step
    for p in problems/*.ini; do
        name=$(basename "$p" .ini)
        echo "problem/$name $name --t-end $t_end"
    done
    echo "demo problems/hang.ini --frames 0"
    "$old" list | sed -n '/^integrators:/,/^force terms:/p' | sed '1d;$d' |
    while read -r name _; do
        case $name in
            fe|symplectic-euler|symplectic-euler-x|verlet|velocity-verlet|rk4)
                step="--dt 1e-5" ;;
            verlet-pbd) step="--dt 1e-5 --set pbd.enabled=true" ;;
            kinsol-*|semi-*) step="--dt 1e-3" ;;
            *) step="" ;;
        esac
        echo "integrator/$name hang --set cloth.n=8 --integrator $name" \
             "$step --t-end 0.05 --samples 20 --frames 0"
    done
    "$old" run spring2 --integrator semi-be --dt 0.01 --t-end 0.01 \
        --linsol / --out "$outdir/none" 2>&1 |
        sed -n 's/.*(known: \(.*\))$/\1/p' | tr -d ' ' | tr , '\n' |
    while read -r name; do
        echo "linsol/semi-bdf2-$name hang --integrator semi-bdf2" \
             "--linsol $name --dt 1e-3 --t-end 0.2 --frames 0"
        echo "linsol/cvode-bdf-$name hang --integrator cvode-bdf" \
             "--linsol $name --t-end 0.2 --frames 0"
    done
    cat <<EOF
test/frames-vtk-obj hang --set cloth.n=6 --t-end 0.05 --integrator symplectic-euler --dt 1e-4 --frames 2
test/frames-csv hang --set cloth.n=6 --t-end 0.01 --integrator symplectic-euler --dt 1e-4 --format csv
test/series hang --set cloth.n=6 --integrator symplectic-euler --dt 1e-3 --t-end 0.05 --samples 200 --frames 0
test/frames-vtk hang --set cloth.n=3 --integrator symplectic-euler --dt 1e-3 --t-end 0.005 --samples 5 --frames 10 --format vtk
test/blow-up hang --set cloth.n=6 --integrator symplectic-euler --dt 0.01 --t-end 1 --samples 100 --frames 0
test/compare-cvode hang --set cloth.n=8 --t-end 0.2 --integrator cvode-bdf --rtol 1e-8 --atol 1e-10 --samples 10 --frames 0
test/compare-symplectic hang --set cloth.n=8 --t-end 0.2 --integrator symplectic-euler --dt 2e-5 --samples 10 --frames 0
test/threads hang --threads 2 --t-end 0.5 --frames 0
test/drape-cvode-bdf drape-sphere --t-end 0.4 --frames 0 --integrator cvode-bdf
test/drape-semi-bdf2 drape-sphere --t-end 0.4 --frames 0 --integrator semi-bdf2 --dt 0.01
test/drape-semi-be drape-sphere --t-end 0.4 --frames 0 --integrator semi-be --dt 0.01
test/drape-kinsol-bdf2 drape-sphere --t-end 0.4 --frames 0 --integrator kinsol-bdf2 --dt 0.01
test/drape-symplectic drape-sphere --t-end 0.4 --frames 0 --integrator symplectic-euler --dt 1e-4
test/tearing verlet-scene3 --t-end 2.0 --frames 1 --format obj
test/verlet-pbd ms-hang --integrator verlet-pbd --t-end 0.1 --frames 0
EOF
}

# Run `clothode run ARGS` with binary $1 into $2/NAME; its exit status
# and messages into $2/NAME.log.
run_one() {
    local bin=$1 dir=$2 name=$3
    shift 3
    rm -rf "${dir:?}/$name"
    mkdir -p "$(dirname "$dir/$name")"
    "$bin" run "$@" --out "$dir/$name" --quiet < /dev/null > "$dir/$name.log" 2>&1
    echo "exit $?" >> "$dir/$name.log"
}

# The files of run $1 that differ between old and new (either missing
# counts as different).
differing() {
    local a=$outdir/old/$1 b=$outdir/new/$1 f
    cmp -s "$a.log" "$b.log" || echo "${1##*/}.log"
    for f in $( (cd "$a" 2>/dev/null && ls; cd "$b" 2>/dev/null && ls) |
                sort -u); do
        if [[ $f == run.json ]]; then
            continue    # provenance: times, paths, the build (README)
        elif [[ $f == stats.csv ]]; then
            cmp -s <(grep -Ev '^(wall|cpu),' "$a/$f" 2>&1) \
                   <(grep -Ev '^(wall|cpu),' "$b/$f" 2>&1)
        else
            cmp -s "$a/$f" "$b/$f"
        fi || echo "$f"
    done
}

start=$SECONDS
status=0 count=0 ndiff=0
while read -r name args; do
    read -ra argv <<< "$args"
    run_one "$old" "$outdir/old" "$name" "${argv[@]}"
    run_one "$new" "$outdir/new" "$name" "${argv[@]}"
    mapfile -t files < <(differing "$name")
    count=$((count + 1))
    if [[ ${#files[@]} -eq 0 ]]; then
        echo "$name: identical"
    else
        more=$((${#files[@]} - 6))
        echo "$name: differs: ${files[*]:0:6}$( ((more > 0)) &&
             echo " (and $more more)")"
        status=1 ndiff=$((ndiff + 1))
    fi
done < <(runs)
echo "compare-outputs: $count runs, $ndiff differ ($((SECONDS - start)) s;" \
     "outputs in $outdir/old, $outdir/new)"
exit $status
