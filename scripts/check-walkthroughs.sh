#!/usr/bin/env bash
# Check the walk-throughs of docs/*.md (docs/extending.md): a walk-through
# is the blocks under one `##` heading whose info strings are
#   c file=PATH               the whole of a new file
#   c insert=PATH before=TEXT lines to insert before the first line of
#                             PATH that contains TEXT
#   sh run                    commands to run from the tree's root
# For each one: copy the tree with its built objects into a scratch
# directory (so that only the changed files compile), apply the blocks,
# build clothode, check that it names something new (`clothode list`, or
# the names --linsol takes), build the test program and run the suites of
# the tests/test_*.c the blocks add or change and those that go over a
# whole registry ($registry_suites); then run the `sh run` commands.
# Any failure names the doc, the heading and the compiler's or program's
# messages.  Run by `make test` (SAN=1: the objects of build-san).
# usage: scripts/check-walkthroughs.sh
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
san=${SAN:-0}
build=build
[[ $san == 1 ]] && build=build-san
jobs=${JOBS:-2}
# the suites whose tests go over a whole registry (docs/extending.md)
registry_suites="linsol shape_registry model spectrum integrator every_integrator
                 constraint memguard kinsol_common numdamp"
cd "$root" || exit 1

scratch=$(mktemp -d "${TMPDIR:-/tmp}/walkthroughs.XXXXXX") || exit 1
trap 'rm -rf "$scratch"' EXIT

fail() { # doc, heading, message; the log follows on stdin
    printf 'check-walkthroughs: FAIL: %s, "%s": %s\n' "$1" "$2" "$3" >&2
    sed 's/^/    /' >&2
    exit 1
}

# The names clothode knows: the first words of `list`'s entries, and the
# linear solvers that an unknown --linsol lists.
names() {
    "$1" list | awk '/^  / { print $1 }'
    "$1" run spring2 --integrator semi-be --dt 0.01 --t-end 0.01 \
        --linsol / --out "$scratch/none" 2>&1 |
        sed -n 's/.*(known: \(.*\))$/\1/p' | tr -d ' ' | tr , '\n'
}

# Split one doc into walk-throughs: $2/N/heading, $2/N/B.kind (file,
# insert or run), $2/N/B.path, $2/N/B.before, $2/N/B.body.
split_doc() {
    awk -v dir="$2" '
        function out(name, text) { printf "%s", text > (wdir "/" nb "." name); close(wdir "/" nb "." name) }
        /^```/ && !fence {
            fence = 1; kind = path = before = ""; info = substr($0, 4)
            if (info ~ /^c file=/) { kind = "file"; path = substr(info, 8) }
            else if (info ~ /^c insert=/) {
                kind = "insert"; rest = substr(info, 10)
                i = index(rest, " before=")
                path = substr(rest, 1, i - 1); before = substr(rest, i + 8)
            } else if (info == "sh run") kind = "run"
            if (kind != "") {
                if (!started) { nw++; started = 1; wdir = dir "/" nw
                                system("mkdir -p \"" wdir "\""); nb = 0
                                printf "%s", heading > (wdir "/heading"); close(wdir "/heading") }
                nb++; body = ""
                out("kind", kind); out("path", path); out("before", before)
            }
            next
        }
        /^```/ && fence { if (kind != "") out("body", body); fence = 0; kind = ""; next }
        fence { if (kind != "") body = body $0 "\n"; next }
        /^## / { heading = substr($0, 4); started = 0 }
    ' "$1"
}

# Apply block $2 of walk-through directory $1 to the tree $3.
apply_block() {
    local b=$1/$2 kind path before
    kind=$(<"$b.kind") path=$(<"$b.path") before=$(<"$b.before")
    case $kind in
        file)
            [[ -e $3/$path ]] && { echo "$path exists already"; return 1; }
            mkdir -p "$(dirname "$3/$path")" && cp "$b.body" "$3/$path" ;;
        insert)
            [[ -f $3/$path ]] || { echo "no file $path"; return 1; }
            awk -v text="$before" -v body="$b.body" '
                !done && index($0, text) { while ((getline l < body) > 0) print l; done = 1 }
                { print }
                END { exit !done }' "$3/$path" > "$3/$path.new" ||
                { echo "no line of $path contains \"$before\""; return 1; }
            mv "$3/$path.new" "$3/$path" ;;
    esac
}

# Build the test program in tree $3 and run each suite $4...: it must
# pass, run at least one test and raise no sanitizer report.  The tests
# that passed are added up in $passed.
check_tests() {
    local doc=$1 heading=$2 tree=$3 log=$scratch/log suite
    shift 3
    MAKEFLAGS= make -C "$tree" -j"$jobs" SAN="$san" "$build/clothode-tests" \
        > "$log" 2>&1 ||
        fail "$doc" "$heading" "the test program does not build" \
            < <(grep -E -A3 'error:|undefined reference' "$log" || tail -20 "$log")
    passed=0
    for suite in "$@"; do
        (cd "$tree" && CLOTHODE=$build/clothode "$build/clothode-tests" \
            --filter "$suite/*") > "$log" 2>&1 ||
            fail "$doc" "$heading" "its tests fail ($suite/*)" < "$log"
        ! grep -qE '(Address|Leak|UndefinedBehavior)Sanitizer|runtime error:' \
            "$log" || fail "$doc" "$heading" "sanitizer reports" < "$log"
        grep -q 'Tested: [1-9]' "$log" ||
            fail "$doc" "$heading" "no test in suite $suite" < "$log"
        passed=$((passed + $(sed -n 's/.*Passing: \([0-9]*\).*/\1/p' "$log")))
    done
}

# Check walk-through directory $1 of doc $2.
check_walkthrough() {
    local w=$1 doc=$2 heading tree=$scratch/tree b suites="" log=$scratch/log
    heading=$(<"$w/heading")
    rm -rf "$tree" && mkdir "$tree"
    cp -a Makefile src tests problems "$tree"/ && cp -a "$build" "$tree"/
    [[ $build != build ]] && ln -s "$build" "$tree/build"
    for b in $(ls "$w" | sed -n 's/\.kind$//p' | sort -n); do
        apply_block "$w" "$b" "$tree" > "$log" 2>&1 ||
            fail "$doc" "$heading" "block $b does not apply" < "$log"
        [[ $(<"$w/$b.path") == tests/test_*.c ]] &&
            suites+=" $(sed -n 's/^Test(\([A-Za-z0-9_]*\),.*/\1/p' \
                        "$tree/$(<"$w/$b.path")" | sort -u | paste -sd' ')"
    done
    MAKEFLAGS= make -C "$tree" -j"$jobs" SAN="$san" "$build/clothode" > "$log" 2>&1 ||
        fail "$doc" "$heading" "build/clothode does not build" \
            < <(grep -E -A3 'error:|undefined reference' "$log" || tail -20 "$log")
    local added
    added=$(comm -13 <(sort -u "$scratch/base-names") \
                     <(names "$tree/$build/clothode" | sort -u) | paste -sd' ')
    [[ -n $added ]] || fail "$doc" "$heading" \
        "clothode list (and --linsol) name nothing new" < /dev/null
    local what="new: $added"
    suites=$(printf '%s\n' $suites $registry_suites | sort -u | paste -sd' ')
    check_tests "$doc" "$heading" "$tree" $suites
    what+="; tests$(printf ' %s/*' $suites): $passed passed"
    for b in $(ls "$w" | sed -n 's/\.kind$//p' | sort -n); do
        [[ $(<"$w/$b.kind") == run ]] || continue
        (cd "$tree" && bash -e "$w/$b.body") > "$log" 2>&1 ||
            fail "$doc" "$heading" "its commands fail" \
                < <(cat "$w/$b.body" - < "$log")
        what+="; ran its commands"
    done
    echo "check-walkthroughs: ok: $doc, \"$heading\" ($what)"
}

MAKEFLAGS= make -j"$jobs" SAN="$san" "$build/clothode" "$build/clothode-tests" \
    > "$scratch/log" 2>&1 ||
    fail "the tree" "" "does not build" < <(tail -20 "$scratch/log")
names "$build/clothode" > "$scratch/base-names"
count=0
for doc in docs/*.md; do
    rm -rf "$scratch/w" && mkdir "$scratch/w"
    split_doc "$doc" "$scratch/w"
    for w in $(ls "$scratch/w" | sort -n); do
        check_walkthrough "$scratch/w/$w" "$doc"
        count=$((count + 1))
    done
done
echo "check-walkthroughs: $count walk-throughs build and pass"
