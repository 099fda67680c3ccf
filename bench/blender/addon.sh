#!/usr/bin/env bash
# The Shatter Fracture add-on against Cell Fracture, side by side in one Blender: the bird
# into 100 Voronoi fragments, the same seeds (a child mesh's vertices) for both operators.
#
# usage: bench/blender/addon.sh [RUNS=5] [N_SEEDS=100] [SEED=1]
#
# Needs (installs nothing): blender 3.4 on PATH with python3-numpy (the glTF importer),
# python3, and the shatter release binary ($SHATTER, else $CARGO_TARGET_DIR/release/shatter,
# else target/release/shatter). Writes to $WORK (default /tmp/shatter-blender-addon-bench).
set -euo pipefail

RUNS=${1:-5}
N=${2:-100}
SEED=${3:-1}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
WORK=${WORK:-/tmp/shatter-blender-addon-bench}

if [[ -z ${SHATTER:-} ]]; then
  if [[ -n ${CARGO_TARGET_DIR:-} && -x $CARGO_TARGET_DIR/release/shatter ]]; then
    SHATTER=$CARGO_TARGET_DIR/release/shatter
  else
    SHATTER=$ROOT/target/release/shatter
  fi
fi
command -v blender >/dev/null || { echo "error: blender not on PATH" >&2; exit 1; }
[[ -x $SHATTER ]] || { echo "error: no shatter binary at $SHATTER (cargo build --release --locked -p shatter-cli, or set SHATTER)" >&2; exit 1; }

mkdir -p "$WORK"
cd "$WORK"
echo "# $(blender --version 2>/dev/null | head -1); $("$SHATTER" --version); $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
"$SHATTER" shape bird --out bird.obj >&2
python3 "$HERE/make_seeds.py" bird.obj seeds.xyz "$N" "$SEED"
bash "$ROOT/blender/package.sh" "$WORK/shatter_fracture.zip" >&2
rm -rf "$WORK/user"
BLENDER_USER_SCRIPTS="$WORK/user/scripts" BLENDER_USER_CONFIG="$WORK/user/config" \
  blender -b --factory-startup --python-exit-code 1 --python "$HERE/addon_vs_cell_fracture.py" \
  -- bird.obj seeds.xyz "$WORK/shatter_fracture.zip" "$SHATTER" "$RUNS" > addon.log 2>&1 \
  || { tail -40 addon.log >&2; exit 1; }
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"

python3 - addon.log <<'PY'
import re, statistics, sys
rows = {"cell": [], "shatter": []}
info = ""
for line in open(sys.argv[1]):
    if line.startswith("INFO "):
        info = line[5:].strip()
    if line.startswith("RESULT "):
        kv = dict(re.findall(r"(\w+)=(\S+)", line))
        rows[kv["tool"]].append(kv)
print("# " + info)
print("| operator (same Blender, same bird, same 100 seeds) | wall time per run | median | fragments | total volume |")
print("|---|---|---|---|---|")
med = {}
for tool, label in (("cell", "Cell Fracture 0.2 (EXACT boolean)"), ("shatter", "Shatter Fracture (export, shatter, OBJ import)")):
    r = rows[tool]
    med[tool] = statistics.median(float(x["seconds"]) for x in r)
    extra = ""
    if tool == "shatter":
        extra = " (shatter's fracture: median %.1f ms)" % statistics.median(float(x["shatter_ms"]) for x in r)
    print("| %s | %s s | %.3f s%s | %s | %s |" % (label, " / ".join("%.3f" % float(x["seconds"]) for x in r), med[tool], extra,
          "/".join(sorted({x["objects"] for x in r})), "/".join(sorted({x["volume"] for x in r}))))
print("\nCell Fracture / Shatter Fracture (median wall): %.1f×" % (med["cell"] / med["shatter"]))
PY
