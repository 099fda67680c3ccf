#!/usr/bin/env bash
# A long sweep of the fracture CLI on a release build, beyond what the tests run: every
# built-in shape, Voronoi with every pattern at 7, 60 and 250 cells and slicing with 3,
# 8 and 20 planes, 8 seeds each (720 runs, a few minutes). A run fails when the command
# fails or warns, when the fragments' volumes do not add up to the mesh's (relative
# error above 1e-6), when a fragment is below the sliver threshold (1e-4 of the
# volume), or when `--validate` (shatter_geom's Fracture::validate: every fragment a
# closed 2-manifold, volumes adding up within 1e-9, a well-formed bond graph) fails.
# Prints each failure and a summary with the count of non-manifold (invalid) results;
# exits 1 if any run failed.
#   bash scripts/fracture-stress.sh [SEEDS=8]
set -uo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/shatter-target}"
cargo build --release --locked -p shatter-cli >&2 || exit 1
bin="$CARGO_TARGET_DIR/release/shatter"
seeds=${1:-8}
err=$(mktemp)
trap 'rm -f "$err"' EXIT
runs=0
bad=0
invalid=0
check() {
    runs=$((runs + 1))
    local out
    if ! out=$("$bin" fracture "$@" --json --validate 2>"$err") || [[ -s $err ]]; then
        bad=$((bad + 1))
        if grep -q "failed validation" "$err"; then
            invalid=$((invalid + 1))
        fi
        echo "FAIL $*: $(head -c 300 "$err")"
        return
    fi
    if ! python3 -c '
import json, sys
d = json.loads(sys.argv[1])
v = d["mesh_volume"]
if abs(d["fragments_volume"] - v) > 1e-6 * v or d["min_fragment_volume"] < 1e-4 * v:
    sys.exit("volumes %r" % d)
' "$out"; then
        bad=$((bad + 1))
        echo "FAIL $*"
    fi
}
for shape in cube capsule cylinder sphere torus bird; do
    for pattern in uniform clustered radial splinter; do
        for pieces in 7 60 250; do
            for seed in $(seq 1 "$seeds"); do
                check --shape "$shape" --method voronoi --pattern "$pattern" --pieces "$pieces" --seed "$seed"
            done
        done
    done
    for pieces in 3 8 20; do
        for seed in $(seq 1 "$seeds"); do
            check --shape "$shape" --method slice --pieces "$pieces" --seed "$seed"
        done
    done
done
echo "fracture stress: $runs runs, $bad failed ($invalid of them not closed 2-manifolds or otherwise invalid by Fracture::validate)"
((bad == 0))
