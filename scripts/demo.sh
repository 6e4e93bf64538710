#!/usr/bin/env bash
# make demo: run the default problem and draw its final state.
# usage: scripts/demo.sh path/to/clothode
set -euo pipefail
bin=${1:-build/clothode}
out=out/demo
"$bin" run problems/hang.ini --out "$out" --frames 0
mkdir -p plots
gnuplot -e "final='$out/final.csv'; outfile='plots/demo.png'" plots/cloth.gp
echo "picture: plots/demo.png"
