#!/usr/bin/env bash
# Install the Debian packages clothode needs, if any are missing.
# Runs apt-get update once, only when something has to be installed.
set -euo pipefail

# python3-numpy, python3-scipy: the scipy peer of the benchmarks
# (scripts/peers/hang_scipy.py), which tests/test_peer.c checks.
# liblapacke-dev: LAPACK's dense LU for cvode-bdf-dense; libopenblas0-serial
# makes it (and GSL's LU, which gsl-msbdf uses, through CBLAS) fast: the
# system's BLAS and LAPACK switch to OpenBLAS, single-threaded so that
# results do not depend on a thread count.
# pkg-config: the installed library's flags, for the example the test
# suite builds against it (scripts/install-check.sh).
pkgs=(build-essential libsundials-dev libsuitesparse-dev libgsl-dev
      liblapacke-dev libopenblas0-serial
      gnuplot-nox libinih-dev libcriterion-dev python3-numpy python3-scipy
      pkg-config)
# libjansson-dev, nettle-dev: run.json (JSON, SHA-256 of the files)
pkgs+=(libjansson-dev nettle-dev)
# Sweeps (README "Sweeps"): the manifest is JSON (Jansson); the jobs run on
# GNU parallel, over ssh, or on Slurm (scripts/slurm-local.sh starts a
# single-node one with munge); the tests start their own sshd.
pkgs+=(parallel openssh-server openssh-client slurm-wlm munge)
# `install-deps.sh paper`: also LaTeX, for make paper only.
if [[ ${1:-} == paper ]]; then
    pkgs+=(texlive-latex-base texlive-latex-recommended
           texlive-fonts-recommended lmodern)
fi
# `install-deps.sh fuzz`: clang-14 and its runtime (libFuzzer, the
# sanitizers), for make fuzz only; valgrind for make memcheck.
if [[ ${1:-} == fuzz ]]; then
    pkgs+=(clang-14 libclang-rt-14-dev valgrind)
fi
# `install-deps.sh multigrid`: petsc4py, for scripts/multigrid-growth.py
# and scripts/deflation-gain.py only (multigrid preconditioners and a
# deflated CG that clothode does not build, measured on its matrices).
if [[ ${1:-} == multigrid ]]; then
    pkgs+=(python3-petsc4py)
fi

missing=()
for p in "${pkgs[@]}"; do
    status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    [[ $status == "install ok installed" ]] || missing+=("$p")
done
((${#missing[@]})) || exit 0

echo "install-deps: installing ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || {
        echo "install-deps: need root (or sudo) to install: ${missing[*]}" >&2
        exit 1
    }
    sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -q
"${sudo[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
