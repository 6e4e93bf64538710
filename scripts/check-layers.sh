#!/bin/sh
# Fails when a file of src/LAYER includes a header of a layer above LAYER
# (docs/architecture.md, "Layer order", whose "layers:" line gives the
# order from the bottom up).  Run from the repository root.
set -eu
order=$(sed -n 's/^<!-- layers: \(.*\) -->$/\1/p' docs/architecture.md)
[ -n "$order" ] || { echo "check-layers: no layers line in docs/architecture.md" >&2; exit 1; }
rank() {
    i=0
    for l in $order; do
        [ "$l" = "$1" ] && { echo $i; return; }
        i=$((i + 1))
    done
    echo -1
}
bad=0
for dir in src/*/; do
    layer=$(basename "$dir")
    own=$(rank "$layer")
    if [ "$own" -lt 0 ]; then
        echo "check-layers: src/$layer is not in the layer order" >&2
        bad=1
        continue
    fi
    for f in "$dir"*.c "$dir"*.h; do
        [ -e "$f" ] || continue
        for inc in $(sed -n 's/^#include "\([a-z_]*\)\/.*/\1/p' "$f" | sort -u); do
            r=$(rank "$inc")
            if [ "$r" -lt 0 ] || [ "$r" -gt "$own" ]; then
                echo "check-layers: $f ($layer) includes $inc/, a layer above it" >&2
                bad=1
            fi
        done
    done
done
[ $bad -eq 0 ] && echo "check-layers: every include points down ($order)"
exit $bad
