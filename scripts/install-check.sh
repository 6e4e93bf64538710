#!/usr/bin/env bash
# The installed clothode as a library user sees it (tests/test_install.c):
# make install into a scratch prefix, build examples/embed_cvode.c against
# it with pkg-config, run it and the installed command on the same cloth,
# and print both final total energies ("example E", "clothode E"), how
# many benchmark objects the installed library holds ("bench_objects"),
# whether a program of one's own finds the plug-in ("plugin found"), and
# the final total energy of a C++ program that integrates the same cloth
# through the library ("cxx E"), how many installed headers do not give
# their declarations C linkage ("unwrapped"), and the example's exit
# status on a problem that needs more than forces ("hooks refused N").
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
# the example integrates forces alone: a problem with projections (PBD)
# is refused, not run without them ("hooks refused N", N its exit status)
status=0
"$prefix/embed_cvode" "$prefix/share/clothode/problems/verlet-scene1.ini" \
    0.01 2> "$prefix/hooks.err" > /dev/null || status=$?
if grep -q "needs more than forces" "$prefix/hooks.err"; then
    echo "hooks refused $status"
else
    cat "$prefix/hooks.err" >&2
    echo "hooks not refused $status"
fi
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
# the installed headers that do not wrap their declarations in
# CL_BEGIN_DECLS (core/decls.h, which defines it, aside)
echo "unwrapped $(grep -L -r --include='*.h' CL_BEGIN_DECLS \
    "$prefix/include/clothode" | grep -v -c '/core/decls\.h$' || true)"
# a C++ program that includes every installed header (core/decls.h:
# C linkage, no C-only syntax), in strict ISO C++14, SUNDIALS' own
# minimum: the library's cvode-bdf on the same cloth as the example, the
# total energy at its end ("cxx E")
( cd "$prefix/include/clothode" && find . -name '*.h' | sort |
      sed 's|^\./\(.*\)|#include "\1"|' ) > "$prefix/own/cxx.cpp"
cat >> "$prefix/own/cxx.cpp" <<'EOF'
#include <cstdio>
#include <vector>

int main(int argc, char **argv)
{
    cl_error err = {};
    cl_model *m = nullptr;
    cl_config *cfg = cl_config_alloc();
    if (argc != 2 || !cfg || cl_config_load(cfg, argv[1], &err) ||
        cl_config_set(cfg, "cloth.n=6", &err) ||
        cl_model_create(cfg, &m, &err)) {
        std::fprintf(stderr, "cxx: %s\n", err.msg);
        cl_config_free(cfg);
        return 1;
    }
    const cl_system *sys = cl_model_system(m);
    const cl_integrator_type *type = cl_integrator_find("cvode-bdf");
    cl_integrator_opts o = {};
    o.rtol = 1e-8;
    o.atol = 1e-10;
    std::vector<double> x(sys->n), v(sys->n);
    void *state = nullptr;
    cl_energy e;
    int bad = !type || cl_model_initial_state(m, x.data(), v.data()) ||
              cl_integrator_create(type, sys, &o, 0.0, x.data(), v.data(),
                                   &state, &err) ||
              type->advance(state, 0.2, x.data(), v.data(), &err) ||
              sys->energy(sys->data, 0.2, x.data(), v.data(), &e);
    if (bad)
        std::fprintf(stderr, "cxx: %s\n", err.msg);
    else
        std::printf("cxx %.17g\n", e.total);
    if (state)
        type->free(state);
    cl_model_free(m);
    cl_config_free(cfg);
    return bad;
}
EOF
c++ -std=c++14 -pedantic -Wall -Wextra -Werror \
    $(pkg-config --cflags clothode) "$prefix/own/cxx.cpp" \
    $(pkg-config --libs clothode) -o "$prefix/own/bin/cxx"
"$prefix/own/bin/cxx" "$prefix/share/clothode/problems/hang.ini"
# by name, from a directory without problems/: the installed ones
cd "$prefix"
bin/clothode run hang --set cloth.n=6 --t-end 0.2 --rtol 1e-8 --atol 1e-10 \
    --frames 0 --out out --quiet
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "total") c = i }
         END { print "clothode", $c }' out/series.csv
