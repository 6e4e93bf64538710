#!/usr/bin/env bash
# The build's provenance as a C header on stdout (src/cli/version.c):
# the version, the git commit (`git describe --always --dirty`, "unknown" outside a git
# checkout), the compiler and its flags.
# usage: scripts/buildinfo.sh CC "FLAGS" VERSION
set -uo pipefail
cd "$(dirname "$0")/.." || exit 1
commit=$(git describe --always --dirty 2>/dev/null) || commit=unknown
[[ -n $commit ]] || commit=unknown
quote() { printf '%s' "$1" | sed 's/[\\"]/\\&/g'; }
printf '#define CL_BUILD_COMMIT "%s"\n' "$(quote "$commit")"
printf '#define CL_BUILD_CC "%s"\n' "$(quote "$1")"
printf '#define CL_BUILD_FLAGS "%s"\n' "$(quote "$2")"
printf '#define CL_BUILD_VERSION "%s"\n' "$(quote "${3:-unknown}")"
