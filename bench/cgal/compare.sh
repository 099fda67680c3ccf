#!/bin/sh
# Side by side: shatter's tetrahedralize vs CGAL 5.5 Delaunay_triangulation_3 on the same
# uniform random points (default 1,000,000): CGAL sequential, CGAL parallel (TBB, every
# core), shatter on every core and shatter on one core (RAYON_NUM_THREADS=1), in turn.
# Needs libcgal-dev and libtbb-dev (apt-get install libcgal-dev libtbb-dev).
# Usage: bench/cgal/compare.sh [N] [RUNS]
set -eu
N=${1:-1000000}
RUNS=${2:-3}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT=${TMPDIR:-/tmp}/shatter-cgal
mkdir -p "$OUT"
g++ -O3 -DNDEBUG -DCGAL_LINKED_WITH_TBB -std=c++17 -o "$OUT/delaunay_cgal" \
  "$HERE/delaunay_cgal.cpp" -lgmp -lmpfr -ltbb -ltbbmalloc
cd "$ROOT"
cargo build --release -q -p shatter-geom --example delaunay_timing
BIN=${CARGO_TARGET_DIR:-$ROOT/target}/release/examples/delaunay_timing
"$BIN" "$N" --write "$OUT/points.xyz" > /dev/null
i=0
while [ "$i" -lt "$RUNS" ]; do
  "$OUT/delaunay_cgal" "$OUT/points.xyz"
  "$OUT/delaunay_cgal" "$OUT/points.xyz" --parallel
  printf 'shatter         '
  "$BIN" --read "$OUT/points.xyz"
  printf 'shatter 1 core  '
  RAYON_NUM_THREADS=1 "$BIN" --read "$OUT/points.xyz"
  i=$((i + 1))
done
