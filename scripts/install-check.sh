#!/usr/bin/env bash
# The installed clothode as a library user sees it (tests/test_install.c):
# make install into a scratch prefix, build examples/embed_cvode.c against
# it with pkg-config, run it and the installed command on the same cloth,
# and print both final total energies ("example E", "clothode E"), how
# many benchmark objects the installed library holds ("bench_objects"),
# and whether a program of one's own finds the plug-in ("plugin found").
# usage: scripts/install-check.sh [build|build-san]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
san=0
[[ $build == build-san ]] && san=1
prefix=$(mktemp -d "${TMPDIR:-/tmp}/clothode-install-XXXXXX")
trap 'rm -rf "$prefix"' EXIT
make -s install PREFIX="$prefix" SAN=$san > /dev/null
# the library holds the numerics, not the benchmark harness (src/bench)
echo "bench_objects $(ar t "$prefix/lib/libclothode.a" | grep -c -E '^(bench|child|main)' || true)"
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
cc -std=c11 -Wall -Wextra -Werror $(pkg-config --cflags clothode) \
    examples/embed_cvode.c $(pkg-config --libs clothode) \
    -o "$prefix/embed_cvode"
"$prefix/embed_cvode" "$prefix/share/clothode/problems/hang.ini" 0.2 \
    cloth.n=6 | awk '$1 == "total" { print "example", $2 }'
# a program of one's own, far from the prefix's bin/, finds the installed
# PETSc plug-in through the installed library (linalg/plugin.h)
mkdir -p "$prefix/own/bin"
printf '%s\n' '#include <stdio.h>' '#include "linalg/plugin.h"' \
    'int main(void) {' '    void *abi; cl_error err;' \
    '    if (cl_plugin_symbol("petsc", "clp_plugin_abi", &abi, &err)) {' \
    '        fprintf(stderr, "%s\n", err.msg); return 1; }' \
    '    puts("plugin found"); return 0; }' > "$prefix/own/plugin.c"
cc -std=c11 -Wall -Wextra -Werror $(pkg-config --cflags clothode) \
    "$prefix/own/plugin.c" $(pkg-config --libs clothode) \
    -o "$prefix/own/bin/plugin"
(unset CLOTHODE_PLUGIN_DIR; "$prefix/own/bin/plugin")
# by name, from a directory without problems/: the installed ones
cd "$prefix"
bin/clothode run hang --set cloth.n=6 --t-end 0.2 --rtol 1e-8 --atol 1e-10 \
    --frames 0 --out out --quiet
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "total") c = i }
         END { print "clothode", $c }' out/series.csv
