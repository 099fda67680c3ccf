#!/usr/bin/env bash
# The user-facing benchmarks on a release build, as reported in closing notes:
#   bash scripts/bench.sh            # full sizes (up to 1,000,000 points)
#   bash scripts/bench.sh --quick    # small sizes, for a smoke run
# Results are printed and also written as JSON to out/bench/.
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/shatter-target}"
sizes="1000,10000,100000,1000000"
runs=5
if [[ "${1:-}" == "--quick" ]]; then
    sizes="1000,10000"
    runs=1
fi
cargo build --release --locked -p shatter-cli
bin="$CARGO_TARGET_DIR/release/shatter"
mkdir -p out/bench
"$bin" bench delaunay --sizes "$sizes"
"$bin" bench delaunay --sizes "$sizes" --json > out/bench/delaunay.json
"$bin" bench fracture --runs "$runs"
"$bin" bench fracture --runs "$runs" --json > out/bench/fracture.json
echo "JSON written to out/bench/"
