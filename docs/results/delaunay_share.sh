#!/usr/bin/env bash
# How much of the creation time at 0 random points is the Delaunay tetrahedralization?
# For each model: the tetrahedralization of its surface vertices alone (`shatter
# tetrahedralize`, best of 5) against the whole tetra fracture (`shatter fracture --json`,
# best of 5; `millis` in both is the computation alone). For the capsule, the same with 50
# random points inside its cylindrical part added to the vertices.
# Usage: bash docs/results/delaunay_share.sh   (SHATTER=path/to/shatter to override)
set -euo pipefail
shatter=${SHATTER:-${CARGO_TARGET_DIR:-$HOME/.cache/shatter-target}/release/shatter}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

millis() { sed -n 's/.*"millis":\([0-9.e+-]*\).*/\1/p'; }
best_of_5() { # best_of_5 CMD...: the smallest "millis" of 5 runs
  for _ in 1 2 3 4 5; do "$@" | millis; done | sort -g | head -1
}
field() { sed -n "s/.*\"$1\":\([0-9]*\).*/\1/p"; }

printf '| model | points | tetrahedra | Delaunay alone [ms] | random points | fracture [ms] | fragments |\n'
printf '| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n'
for model in cube capsule cylinder bird; do
  "$shatter" shape "$model" --out "$tmp/$model.obj" >/dev/null
  awk '$1 == "v" { print $2, $3, $4 }' "$tmp/$model.obj" >"$tmp/$model.xyz"
  tets=$("$shatter" tetrahedralize --input "$tmp/$model.xyz" --json | field tetrahedra)
  unique=$("$shatter" tetrahedralize --input "$tmp/$model.xyz" --json | field unique_points)
  del=$(best_of_5 "$shatter" tetrahedralize --input "$tmp/$model.xyz" --json)
  frac_json=$("$shatter" fracture --shape "$model" --method tetra --random-vertices 0 --json)
  frac=$(best_of_5 "$shatter" fracture --shape "$model" --method tetra --random-vertices 0 --json)
  printf '| %s | %s | %s | %.2f | 0 | %.2f | %s |\n' "$model" "$unique" "$tets" "$del" "$frac" \
    "$(echo "$frac_json" | field fragments)"
done
# The capsule's vertices plus 50 points inside its cylindrical part (|y| < 0.5, r < 0.45).
awk 'BEGIN { srand(1); while (c < 50) { x = rand() - 0.5; z = rand() - 0.5;
  if (x * x + z * z < 0.2) { print x, rand() - 0.5, z; c++ } } }' >"$tmp/inside.xyz"
cat "$tmp/capsule.xyz" "$tmp/inside.xyz" >"$tmp/capsule50.xyz"
tets=$("$shatter" tetrahedralize --input "$tmp/capsule50.xyz" --json | field tetrahedra)
unique=$("$shatter" tetrahedralize --input "$tmp/capsule50.xyz" --json | field unique_points)
del=$(best_of_5 "$shatter" tetrahedralize --input "$tmp/capsule50.xyz" --json)
frac_json=$("$shatter" fracture --shape capsule --method tetra --random-vertices 50 --json)
frac=$(best_of_5 "$shatter" fracture --shape capsule --method tetra --random-vertices 50 --json)
printf '| capsule + 50 inside | %s | %s | %.2f | 50 | %.2f | %s |\n' "$unique" "$tets" "$del" "$frac" \
  "$(echo "$frac_json" | field fragments)"
