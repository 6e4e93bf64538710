#!/usr/bin/env bash
# make report: run the analyses on the default problems, keep their CSV
# tables under results/report/ and draw the figures into plots/ (PNG and
# PDF; an animated GIF of the hanging cloth).  About six minutes of CPU
# time, one process at a time.  usage: scripts/report.sh path/to/clothode
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/clothode}
res=results/report
mkdir -p "$res" plots

# Split a study's CSV (first column: the method) into DIR/NAME.dat with the
# columns given (1-based, whitespace-separated), keeping only the rows whose
# status (last column, when the header ends in "status") is "ok"; print the
# names in order.
split_csv() { # csv dir col...
    local csv=$1 dir=$2
    shift 2
    rm -rf "$dir" && mkdir -p "$dir"
    awk -F, -v dir="$dir" -v cols="$*" '
        NR == 1 { status = $NF == "status"; next }
        status && $NF != "ok" { next }
        { n = split(cols, c, " "); line = ""
          for (i = 1; i <= n; i++) line = line (i > 1 ? " " : "") $c[i]
          if (!($1 in seen)) { seen[$1] = 1; order[++m] = $1 }
          print line > (dir "/" $1 ".dat") }
        END { for (i = 1; i <= m; i++) printf "%s%s", (i > 1 ? " " : ""), order[i] }' "$csv"
}

# Plan problems/sweeps/NAME.ini into DIR/sweep, run it on GNU parallel (REPORT_JOBS
# jobs at a time, default one per core) and collect it into DIR/sweep.csv.
sweep() { # name dir
    local name=$1 dir=$2
    rm -rf "$dir/sweep"
    "$bin" sweep plan "problems/sweeps/$name.ini" --out "$dir/sweep" --quiet
    "$bin" sweep run "$dir/sweep" --engine local --jobs "${REPORT_JOBS:-0}" \
        --quiet
    "$bin" sweep collect "$dir/sweep" --out "$dir/sweep.csv" | grep " complete, "
}

# Draw plots/NAME.png and plots/NAME.pdf with plots/NAME.gp.
draw() { # name gnuplot-assignments
    local name=$1 vars=$2
    for term in png pdf; do
        gnuplot -e "term='$term'; outfile='plots/$name.$term'; $vars" \
            "plots/${3:-$name}.gp"
    done
    echo "  plots/$name.png, .pdf"
}

echo "report: convergence (spring2)"
"$bin" convergence spring2 --quiet --out "$res/convergence" --t-end 1 \
    --dt 1e-2 --levels 5 --integrator \
    fe,symplectic-euler,symplectic-euler-x,verlet,velocity-verlet,rk4,semi-be,semi-bdf2,kinsol-midpoint
names=$(split_csv "$res/convergence/convergence.csv" "$res/convergence/dat" 3 4)
draw convergence "dir='$res/convergence/dat'; names='$names'; title_text='spring2, T = 1 s: position error against dt'; xlabel_text='dt (s)'"

echo "report: work-precision (hang, T = 0.2 s), the runs of problems/sweeps/workprecision.ini"
sweep workprecision "$res/workprecision"
"$bin" workprecision hang --quiet --out "$res/workprecision" --t-end 0.2 \
    --from-sweep "$res/workprecision/sweep.csv" --integrator \
    cvode-bdf:klu,cvode-bdf:pcg,semi-bdf2:klu,semi-bdf2:pcg,rk4
names=$(split_csv "$res/workprecision/workprecision.csv" "$res/workprecision/dat" 4 11)
draw workprecision "dir='$res/workprecision/dat'; names='$names'; title_text='hang 16 x 16, T = 0.2 s: CPU time against error'"

echo "report: work-precision of every method on hang n = 16 and 32 (T = 0.01 s)"
# Every integrator of the registry (list --integrators fixed, adaptive):
# one sweep over both sizes, fixed steps T/10 .. T/80, tolerances 1e-4 ..
# 1e-7, against cvode-bdf at rtol 1e-11; a figure per size.  Each run
# stops after 5 s of wall time, checked at its 20 samples (status budget,
# left out of the figure).  kinsol-* and semi-* solve with pcg: at n = 32
# KLU's factorisation every step costs them 0.1 to 0.2 s of CPU a step,
# pcg 2 to 5 ms, so that with KLU only their largest steps ran within the
# budget.  The methods with no run at a size are named, with why, on its
# figure.
wpa=$res/workprecision-all
rm -rf "$wpa" && mkdir -p "$wpa"
fixed=$("$bin" list --integrators fixed |
    sed -E 's/(kinsol|semi)-([a-z0-9]+)/\1-\2:pcg/g')
adaptive=$("$bin" list --integrators adaptive)
cat > "$wpa/all.ini" <<EOF
[sweep]
problem = $PWD/problems/hang.ini
reference = 1e-11
t_end = 0.01
n = 16, 32
run.samples = 20
run.budget_wall = 5
EOF
# One section per six methods: an INI line holds at most 197 characters.
sections() { # kind list axis-lines...
    local kind=$1 list=$2 k=0
    shift 2
    echo "$list" | tr , '\n' | paste -d, - - - - - - | sed 's/,*$//' |
    while read -r part; do
        k=$((k + 1))
        printf '\n[sweep.%s%d]\nintegrator = %s\n' "$kind" "$k" "$part"
        printf '%s\n' "$@"
    done
}
sections fixed "$fixed" "dt = 1e-3, 5e-4, 2.5e-4, 1.25e-4" >> "$wpa/all.ini"
sections adaptive "$adaptive" "rtol = 1e-4, 1e-5, 1e-6, 1e-7" \
    "atol = rtol / 100" >> "$wpa/all.ini"
"$bin" sweep plan "$wpa/all.ini" --out "$wpa/sweep" --quiet
"$bin" sweep run "$wpa/sweep" --engine local --jobs "${REPORT_JOBS:-0}" --quiet
"$bin" sweep collect "$wpa/sweep" --out "$wpa/sweep.csv" | grep " complete, "
# The methods of KIND with a complete run at size N (a method the problem
# refuses, verlet-pbd without [pbd], a dense one above its size, has none).
ran() { # kind n
    awk -F, -v list="${!1}" -v n="$2" '
        NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
        $2 == "job" && $c["cloth.n"] == n && $c["status"] == "complete" { ok[$3] = 1 }
        END { m = split(list, l, ","); s = ""
              for (i = 1; i <= m; i++) if (l[i] in ok) s = s (s == "" ? "" : ",") l[i]
              print s }' "$wpa/sweep.csv"
}
# The methods with no complete run at size N, each with the exit class of
# its runs (budget: the wall-time budget, with the latest time reached).
missing() { # n
    awk -F, -v n="$1" '
        NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
        $2 != "job" || $c["cloth.n"] != n { next }
        { m = $3; if (!(m in seen)) { seen[m] = 1; order[++k] = m }
          if ($c["status"] == "complete") ok[m] = 1
          why[m] = $c["exit"]
          if ($c["t_reached"] + 0 > t[m]) t[m] = $c["t_reached"] + 0 }
        END { s = ""
              for (i = 1; i <= k; i++) { m = order[i]; if (m in ok) continue
                  s = s (s == "" ? "" : ++j % 3 ? ", " : ",\\n") m " (" why[m]
                  if (why[m] == "budget") s = s sprintf(" at t = %g s", t[m])
                  s = s ")" }
              print s }' "$wpa/sweep.csv"
}
for n in 16 32; do
    # six methods a call, as in the sweep's sections: the integrator list
    # is written back into an INI line of at most 197 characters
    parts=()
    for kind in fixed adaptive; do
        k=0
        for part in $(ran "$kind" "$n" | tr , '\n' | paste -d, - - - - - - |
                      sed 's/,*$//'); do
            k=$((k + 1))
            "$bin" workprecision hang --quiet --out "$wpa/n$n/$kind$k" \
                --t-end 0.01 --set cloth.n="$n" \
                --from-sweep "$wpa/sweep.csv" --integrator "$part"
            parts+=("$wpa/n$n/$kind$k/workprecision.csv")
        done
    done
    head -n 1 "${parts[0]}" > "$wpa/n$n/workprecision.csv"
    for f in "${parts[@]}"; do
        tail -n +2 "$f" >> "$wpa/n$n/workprecision.csv"
    done
    names=$(split_csv "$wpa/n$n/workprecision.csv" "$wpa/n$n/dat" 4 11)
    gone=$(missing "$n")
    echo "  n = $n, no point: ${gone:-none}" | sed 's/\\n/ /g'
    draw "workprecision-$n" "dir='$wpa/n$n/dat'; names='$names'; title_text='hang $n x $n, T = 0.01 s: CPU time against error, every method'; note_text=\"no point (5 s of wall time per run): ${gone:-none}\"" workprecision
done

echo "report: energy balance (hang-smooth, undamped)"
"$bin" energy hang-smooth --quiet --out "$res/energy" --t-end 2 --dt 5e-4 \
    --samples 2000 --integrator \
    symplectic-euler,velocity-verlet,rk4,semi-be,semi-bdf2,kinsol-midpoint
names=$(split_csv "$res/energy/energy.csv" "$res/energy/dat" 2 7)
draw energy "dir='$res/energy/dat'; names='$names'; title_text='hang-smooth, dt = 5e-4 s: energy balance B(t)'"

echo "report: explicit step limits, spectrum against stability"
# The spectral predictions and the measured brackets of the integrators
# LIST on hang-like PROBLEM (T = 2 s) into DIR/limits.txt, one row
# "integrator predicted largest-stable smallest-unstable" each; with
# from=TABLE the brackets come from a collected sweep.
limits() { # dir problem list [--set ...]
    local dir=$1 problem=$2 list=$3
    shift 3
    "$bin" stability "$problem" "$@" --quiet --out "$dir" --t-end 2 \
        --integrator "$list" ${from:+--from-sweep "$from"}
    "$bin" spectrum "$problem" "$@" --out "$dir" |
        awk '$2 ~ /^[0-9.e+-]+$/ && NF >= 3 { print $1, $2 }' \
            > "$dir/predicted.txt"
    awk -F, 'NR > 1 && $4 == 1 { if (!($1 in s) || $2 > s[$1]) s[$1] = $2 }
             NR > 1 && $4 == 0 { if (!($1 in u) || $2 < u[$1]) u[$1] = $2 }
             END { for (k in s) print k, s[k], (k in u ? u[k] : "nan") }' \
        "$dir/stability.csv" > "$dir/measured.txt"
    awk 'NR == FNR { p[$1] = $2; next } ($1 in p) { print $1, p[$1], $2, $3 }' \
        "$dir/predicted.txt" "$dir/measured.txt" | sort > "$dir/limits.txt"
}
for p in hang-smooth hang; do
    limits "$res/limits/$p" "$p" symplectic-euler,velocity-verlet,verlet,rk4,fe
    draw "limits-$p" "data='$res/limits/$p/limits.txt'; title_text='$p: explicit step limits, T = 2 s'" limits
    draw "spectrum-$p" "data='$res/limits/$p/spectrum.csv'; title_text='$p at rest: first-order eigenvalues'" spectrum
done

echo "report: stability map, explicit limits of hang against the grid size (problems/sweeps/map.ini)"
# "n method predicted largest-stable smallest-unstable" per size and method,
# the brackets from the sweep's grid of steps.
map=$res/limits/map
rm -rf "$map" && mkdir -p "$map"
sweep map "$map"
# two more stages inside the brackets (sweep refine): 62 % -> 10 % -> 2 %
tables=$map/sweep.csv
for stage in 1 2; do
    "$bin" sweep refine "$map/sweep" --table "$tables" --points 4 \
        --out "$map/refine$stage" --quiet
    "$bin" sweep run "$map/refine$stage" --engine local \
        --jobs "${REPORT_JOBS:-0}" --quiet
    "$bin" sweep collect "$map/refine$stage" --out "$map/refine$stage.csv" |
        grep " complete, "
    tables=$tables,$map/refine$stage.csv
done
for n in 6 8 12 16; do
    from=$tables limits "$map/n$n" hang symplectic-euler,rk4 \
        --set cloth.n="$n"
    awk -v n="$n" '{ print n, $0 }' "$map/n$n/limits.txt" >> "$map/map.txt"
done
sort -k2,2 -k1,1n "$map/map.txt" -o "$map/map.txt"
cat "$map/map.txt"
for m in symplectic-euler rk4; do
    awk -v m="$m" '$2 == m { print $1, $3, $4 }' "$map/map.txt" > "$map/$m.dat"
done
draw map "dir='$map'; names='symplectic-euler rk4'; title_text='hang, T = 2 s: explicit step limit against grid size'"

echo "report: stability against stiffness (hang n = 6, type1.ks = 1e2 .. 1e7)"
# Every fixed-step method of the registry (list --integrators): the search
# at each ks beside the spectrum's prediction, one process per kind and
# value on GNU parallel; "NAME.dat: ks stable unstable predicted" and the
# fitted slopes of log dt against log ks (slopes.txt).
st=$res/stiffness
rm -rf "$st" && mkdir -p "$st"
stiff() { # kind ks
    "$bin" stability hang --quiet --set cloth.n=6 --t-end 0.1 --dt-max 0.01 \
        --dt-min 1e-6 --rel 0.05 --out "$st/$1-$2" --axis "type1.ks=$2" \
        --integrator "$("$bin" list --integrators "$1")"
}
export -f stiff
export bin st
parallel -j "${REPORT_JOBS:-100%}" stiff ::: explicit implicit ::: \
    1e2 1e3 1e4 1e5 1e6 1e7
awk -F, -v dir="$st" 'FNR > 1 { print $2, $3, $4, $5 > (dir "/" $1 ".dat") }' \
    "$st"/*/limits.csv
for f in "$st"/*.dat; do sort -g "$f" -o "$f"; done
awk 'function fit(n, x, y,   i, sx, sy, sxx, sxy) {
         for (i = 1; i <= n; i++) {
             sx += x[i]; sy += y[i]; sxx += x[i] * x[i]; sxy += x[i] * y[i] }
         return n < 2 ? "nan" : sprintf("%.3f", (n * sxy - sx * sy) / (n * sxx - sx * sx)) }
     FNR == 1 { if (m) out(); m = split(FILENAME, p, "/"); name = p[m]
                sub(/\.dat$/, "", name); nm = np = 0 }
     $2 + 0 > 0 && $3 + 0 > 0 { nm++; xm[nm] = log($1); ym[nm] = log(sqrt($2 * $3)) }
     $4 + 0 > 0 && $4 != "inf" { np++; xp[np] = log($1); yp[np] = log($4) }
     function out() { print name, fit(nm, xm, ym), fit(np, xp, yp) }
     END { out() }' "$st"/*.dat | tee "$st/slopes.txt"
names=$(cd "$st" && ls ./*.dat | sed 's|^\./||; s|\.dat$||' | tr '\n' ' ')
draw stiffness "dir='$st'; names='$names'; title_text='hang 6 x 6, T = 0.1 s: largest stable step against ks'"

echo "report: inverse sinc and counts"
"$bin" asinc --points 1000 --csv > "$res/asinc.csv"
draw asinc "data='$res/asinc.csv'; title_text='Type2 curvature: asinc against the polynomial of Jiao'"
"$bin" counts --csv --n-max 64 > "$res/counts.csv"
draw counts "data='$res/counts.csv'; title_text='Choi-Ko connections: measured (points) and formulas (lines)'"

echo "report: the sources' claims on their own configurations"
scripts/claims.sh "$bin" "$res/claims"
# The K x U x iterations map as "K U iterations k kd", bounded and blown up.
awk -F, -v dir="$res/claims" 'NR > 1 { print $1, $2, $3, $4, $5 > (dir "/" ($6 ? "stable" : "blowup") ".dat") }' \
    "$res/claims/map.csv"
read -r k0 d0 < "$res/claims/map-line.txt"
draw claims-map "dir='$res/claims'; k0=$k0; d0=$d0; title_text='verlet-drop at 1/60 s: spring and friction, K x U x constraint iterations'"

echo "report: wrinkles under large steps (compress, T = 1 s)"
# The final out-of-plane amplitude and wrinkle count of every run, or how
# far it got before it blew up: "method dt t_reached amplitude wrinkles".
wr=$res/wrinkles
rm -rf "$wr" && mkdir -p "$wr"
wrinkle_run() { # table label dir args...
    local table=$1 label=$2 dir=$3
    shift 3
    local status=ok
    "$bin" run compress --quiet --frames 0 --samples 100 --out "$dir" "$@" \
        2> "$dir.err" || status=blow-up
    awk -F, -v l="$label" -v s="$status" 'NR > 1 { t = $1; a = $(NF - 2); w = $(NF - 1) }
        END { print l, t, a, w, s }' "$dir/series.csv" >> "$table"
    awk -F, 'NR > 1 { print $1, $(NF - 2) }' "$dir/series.csv" > "$dir.dat"
}
wrinkle_run "$wr/wrinkles.txt" "cvode-bdf rtol=1e-6" "$wr/reference"
names="reference"
for m in semi-be semi-bdf2; do
    for dt in 1e-3 2e-3 5e-3 1e-2 2e-2; do
        wrinkle_run "$wr/wrinkles.txt" "$m dt=$dt" "$wr/$m-$dt" \
            --integrator "$m" --dt "$dt"
    done
    names="$names $m-1e-3 $m-5e-3 $m-1e-2"
done
cat "$wr/wrinkles.txt"
draw wrinkles "dir='$wr'; names='$names'; title_text='compress: largest out-of-plane displacement'"

echo "report: the formed wrinkle under large steps (compress from t = 1 s to 2 s)"
# The reference's state at t = 1 s (the ends stopped at 0.4 s), continued
# to 2 s ([init] state and time) by each method, as above.
formed=(--set "init.state=$wr/reference/final.csv" --set init.time=1
        --set init.perturb=0)
wrinkle_run "$wr/kept.txt" "cvode-bdf rtol=1e-6" "$wr/kept-reference" \
    --t-end 2 "${formed[@]}"
for m in semi-be semi-bdf2; do
    for dt in 1e-2 5e-2 1e-1 2e-1 5e-1 1; do
        wrinkle_run "$wr/kept.txt" "$m dt=$dt" "$wr/kept-$m-$dt" \
            --integrator "$m" --dt "$dt" --t-end 2 "${formed[@]}"
    done
done
cat "$wr/kept.txt"
# the stiffness of the formed state and of the strip being pushed (the
# reference at t = 0.2 s): their negative eigenvalues
echo "formed, t = 1 s:"
"$bin" spectrum compress "${formed[@]}" --out "$wr/formed-spectrum" |
    grep -E '^(stiffness|first order)'
"$bin" run compress --t-end 0.2 --frames 0 --quiet --out "$wr/pushed"
echo "pushed, t = 0.2 s:"
"$bin" spectrum compress --state "$wr/pushed/final.csv" --t 0.2 \
    --out "$wr/pushed-spectrum" | grep -E '^(stiffness|first order)'

echo "report: predictability of hang (n = 10), cvode-bdf against rtol 1e-11"
scripts/hang-sensitivity.sh 10 0.2 0.5 > "$res/sensitivity.txt"
cat "$res/sensitivity.txt"
echo "report: why (mirror asymmetry; bending, damping and Type2 varied)"
scripts/hang-mechanism.sh symmetry 10 0.2 0.3 0.5 1.0 > "$res/symmetry.txt"
scripts/hang-mechanism.sh variants 10 0.5 > "$res/variants.txt"
cat "$res/symmetry.txt" "$res/variants.txt"

echo "report: contact (skirt; drape-sphere at several steps)"
ct=$res/contact
rm -rf "$ct" && mkdir -p "$ct"
"$bin" run skirt --quiet --out "$ct/skirt" --frames 4 --format obj
last=$(ls "$ct"/skirt/frame_*.obj | tail -1)
draw skirt "cloth='$last'; obstacles='${last/frame_/obstacles_}'; title_text='skirt: the last frame, t = 4 s'" scene
# Every run: "method step worst_penetration_m at_s steps cpu_s status"
# (step "-" for CVODE), and the penetration over time as LABEL.dat.
contact_run() { # method [step]
    local label=$1${2:+-$2} status=ok
    local dir=$ct/$label
    "$bin" run drape-sphere --frames 2 --format obj --out "$dir" \
        --integrator "$1" ${2:+--dt "$2"} > "$dir.out" 2>&1 || status=failed
    awk -v m="$1" -v h="${2:--}" -v s="$status" '
        $1 == "contact" { w = $4; at = $9 } $1 == "steps" { n = $2 }
        $1 == "cpu" { c = $4 } $1 == "time" { t = $2 }
        END { print m, h, w, at, n, c, (s == "ok" ? s : s "@" t) }' \
        "$dir.out" >> "$ct/drape.txt"
    awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "max_penetration") c = i }
        NR > 1 { print $1, $c }' "$dir/series.csv" > "$ct/$label.dat"
    names="$names $label"
}
names=""
for run in "cvode-bdf" "symplectic-euler 1e-4" "semi-be 1e-2" "semi-be 4e-2" \
           "semi-bdf2 1e-2" "semi-bdf2 2e-2" "semi-bdf2 4e-2" \
           "kinsol-bdf2 1e-2" "kinsol-bdf2 4e-2"; do
    contact_run $run
done
cat "$ct/drape.txt"
last=$(ls "$ct"/semi-bdf2-1e-2/frame_*.obj | tail -1)
draw drape-sphere "cloth='$last'; obstacles='${last/frame_/obstacles_}'; title_text='drape-sphere, semi-bdf2 dt = 0.01: t = 3 s'" scene
draw penetration "dir='$ct'; names='$names'; title_text='drape-sphere: deepest penetration into the sphere or the floor'"

echo "report: contact study (jiao-sphere against dt; tunnel against speed)"
cs=$res/contact-study
rm -rf "$cs" && mkdir -p "$cs"
# Jiao's cloth on his sphere with Choi and Ko's BDF2 step, the code's
# projection beside a penalty spring (k = 1 N/m: 1 cm of rest depth under
# the code's 0.01 N a particle); unstable: d/L > 3 (the cloth alone swings
# to 1.73 at these steps).
"$bin" contact jiao-sphere --quiet --out "$cs/jiao-sphere" --integrator semi-bdf2 \
    --response project,penalty --set obstacle.sphere.k=1 \
    --dt 2e-3,5e-3,1e-2,2e-2 --t-end 0.5 --checks 100 --set run.max_stretch=3
awk -F, -v dir="$cs" 'NR > 1 { print $3, $7, $11, $5 > (dir "/" $2 ".dat") }' \
    "$cs/jiao-sphere/contact.csv"
# tunnel: the sphere of radius 0.2 m at speed V (T = 0.6 / V), semi-be at
# 1e-3 s: "V worst_penetration contacts_at_T" per response.
for v in 1 10 30 100 150 200 300 600; do
    "$bin" contact tunnel --quiet --out "$cs/tunnel-$v" --integrator semi-be \
        --response penalty,project --dt 1e-3 --t-end "$(awk -v v=$v 'BEGIN { print 0.6 / v }')" \
        --set "obstacle.ball.path=0: 0, 0, 0; 1: 0, $v, 0"
    awk -F, -v dir="$cs" -v v=$v 'NR > 1 { print v, $7, $10 >> (dir "/tunnel-" $2 ".dat") }' \
        "$cs/tunnel-$v/contact.csv"
done
cat "$cs/jiao-sphere/contact.csv" "$cs"/tunnel-*.dat
draw contact-study "dir='$cs'; title_text='contact study'"

echo "report: numerical damping (spring2 against w h; hang-smooth's modes, at rest and prestressed)"
nd=$res/damping
rm -rf "$nd" && mkdir -p "$nd"
"$bin" damping spring2 --quiet --out "$nd" --wh 0.1:100:13 --steps 200
names=$(split_csv "$nd/damping.csv" "$nd/dat" 2 4 5)
draw damping "dir='$nd/dat'; names='$names'; title_text='spring2: amplitude ratio per step, measured (points) and theory (lines), rho_inf = 0.5'"
"$bin" damping hang-smooth --out "$nd" --set gravity.g=0,0,0 --modes 1 \
    --modes-dt 1e-2
names=$(split_csv "$nd/damping-modes.csv" "$nd/modes" 4 5 6)
draw damping-modes "dir='$nd/modes'; names='$names'; title_text='hang-smooth at rest, no gravity: energy left per mode after 1 s at dt = 0.01'"
# The prestressed cloth: hang-smooth hanging in its plane from its pinned
# edge (gravity along the cloth, compressed pairs slack), at its static
# equilibrium, where tension gives the out-of-plane (wrinkle) modes a
# stiffness; their energy left (normal fraction > 1/2) in a figure of its
# own.  The speed keeps the motion linear (about 3 s).
"$bin" damping hang-smooth --out "$nd/hanging" --set gravity.g=9.81,0,0 \
    --set pins.at=i=0 --set type1.compression=none --modes 1 --equilibrium \
    --speed 1e-7
awk -F, 'NR == 1 || $7 > 0.5' "$nd/hanging/damping-modes.csv" \
    > "$nd/hanging/out-of-plane.csv"
names=$(split_csv "$nd/hanging/out-of-plane.csv" "$nd/wrinkles" 4 5 6)
draw damping-wrinkles "dir='$nd/wrinkles'; names='$names'; title_text='hang-smooth hanging at equilibrium: out-of-plane modes, 1 s at dt = 0.01'" damping-modes
echo "report: equal budget (xpbd-chain; ms-hang springs), substeps against iterations"
bd=$res/budget
rm -rf "$bd" && mkdir -p "$bd"
"$bin" budget xpbd-chain --quiet --out "$bd/chain" --integrator xpbd \
    --budget 20 --dt 0.01 --t-end 1 --ref-rtol 0
awk -F, 'NR > 1 { print $3, $7, $8 }' "$bd/chain/budget.csv" > "$bd/chain.dat"
"$bin" budget ms-hang --quiet --out "$bd/hang" --budget 8 --dt 0.01 \
    --t-end 0.5 --ref-rtol 1e-8 --set pbd.enabled=false \
    --set spring-damping.kd=0 \
    --integrator xpbd,pd,kinsol-be,semi-be,kinsol-bdf2,semi-bdf2
names=$(split_csv "$bd/hang/budget.csv" "$bd/dat" 3 6 13)
cat "$bd/chain/budget.csv" "$bd/hang/budget.csv"
draw budget "chain='$bd/chain.dat'; dir='$bd/dat'; names='$names'; title_text='equal budget: substeps against iterations'"

echo "report: animation (hang, cvode-bdf, 2 s)"
"$bin" run hang --quiet --out "$res/hang" --frames 40 --format obj
gnuplot -e "dir='$res/hang'; nframes=40; nv=16; outfile='plots/hang.gif'; xr0=-0.6; xr1=1.1; zr0=0; zr1=1; yr0=-1.1; yr1=0.1" plots/animation.gp
echo "  plots/hang.gif"
echo "report: tables in $res, figures in plots/"
