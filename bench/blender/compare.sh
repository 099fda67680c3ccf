#!/usr/bin/env bash
# shatter vs Blender's Cell Fracture add-on: the bird into 100 Voronoi fragments, same seeds.
#
# usage: bench/blender/compare.sh [RUNS=5] [N_SEEDS=100] [SEED=1]
#
# Needs (installs nothing):
#   - blender 3.4 on PATH (Debian 12: apt-get install --no-install-recommends blender),
#     which ships the Cell Fracture add-on (object_fracture_cell)
#   - python3 (plain, no numpy)
#   - the shatter release binary: $SHATTER, else $CARGO_TARGET_DIR/release/shatter,
#     else target/release/shatter (cargo build --release --locked -p shatter-cli)
# Generated files go to $WORK (default /tmp/shatter-blender-bench), never into the repo.
# Runs are sequential (never concurrent). Per round: Blender with the add-on as shipped
# (EXACT boolean solver, all cores), the same with `blender -t 1` (one thread), the FAST
# solver (patched in memory, all cores), then shatter on all cores and on one
# (RAYON_NUM_THREADS=1).
set -euo pipefail

RUNS=${1:-5}
N=${2:-100}
SEED=${3:-1}
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
WORK=${WORK:-/tmp/shatter-blender-bench}

if [[ -z ${SHATTER:-} ]]; then
  if [[ -n ${CARGO_TARGET_DIR:-} && -x $CARGO_TARGET_DIR/release/shatter ]]; then
    SHATTER=$CARGO_TARGET_DIR/release/shatter
  else
    SHATTER=$ROOT/target/release/shatter
  fi
fi
missing=0
command -v blender >/dev/null || { echo "error: blender not on PATH (apt-get install --no-install-recommends blender)" >&2; missing=1; }
command -v python3 >/dev/null || { echo "error: python3 not on PATH" >&2; missing=1; }
[[ -x $SHATTER ]] || { echo "error: no shatter binary at $SHATTER (cargo build --release --locked -p shatter-cli, or set SHATTER)" >&2; missing=1; }
(( missing == 0 )) || exit 1

mkdir -p "$WORK"
cd "$WORK"
echo "# $(blender --version 2>/dev/null | head -1); $("$SHATTER" --version); $(nproc) cores; $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //')"
"$SHATTER" shape bird --out bird.obj >&2
python3 "$HERE/make_seeds.py" bird.obj seeds.xyz "$N" "$SEED"

: > results.txt
configs=("as shipped (EXACT boolean), 2 threads|--solver EXACT|" "as shipped (EXACT boolean), -t 1|--solver EXACT|-t 1" "FAST boolean (patched), 2 threads|--solver FAST|")
for ((r = 1; r <= RUNS; r++)); do
  for c in "${configs[@]}"; do
    IFS='|' read -r label solver threads <<< "$c"
    echo "load $(cut -d' ' -f1-3 /proc/loadavg)" >> results.txt
    # shellcheck disable=SC2086
    blender -b $threads --factory-startup --python "$HERE/cell_fracture.py" -- bird.obj seeds.xyz \
      $solver > blender.log 2>&1 || { cat blender.log >&2; exit 1; }
    echo "CONFIG $label $(grep '^RESULT' blender.log)" >> results.txt
  done
  echo "load $(cut -d' ' -f1-3 /proc/loadavg)" >> results.txt
  echo "SHATTER $("$SHATTER" fracture --shape bird --method voronoi --seeds-file seeds.xyz --out shatter.obj --json)" >> results.txt
  echo "load $(cut -d' ' -f1-3 /proc/loadavg)" >> results.txt
  echo "SHATTER1 $(RAYON_NUM_THREADS=1 "$SHATTER" fracture --shape bird --method voronoi --seeds-file seeds.xyz --json)" >> results.txt
done

python3 - results.txt <<'PY'
import json, re, statistics, sys
blender = {}
shatter, shatter1, loads, info = [], [], [], {}
for line in open(sys.argv[1]):
    if line.startswith("load "):
        loads.append(line.split()[1])
    elif line.startswith("CONFIG "):
        label = line[len("CONFIG "):line.index(" RESULT ")]
        kv = dict(re.findall(r"(\w+)=(\S+)", line))
        blender.setdefault(label, []).append((float(kv["blender_seconds"]), float(kv["cpu_seconds"]), int(kv["objects"]), float(kv["volume"])))
        info["mesh_volume"] = kv["mesh_volume"]
    elif line.startswith("SHATTER "):
        j = json.loads(line[len("SHATTER "):])
        shatter.append((j["millis"], j["fragments"], j["fragments_volume"]))
    elif line.startswith("SHATTER1 "):
        j = json.loads(line[len("SHATTER1 "):])
        shatter1.append((j["millis"], j["fragments"], j["fragments_volume"]))
sm = statistics.median(m for m, _, _ in shatter)
sm1 = statistics.median(m for m, _, _ in shatter1)
print("| | wall time per run (CPU time, all threads) | median wall | fragments | total volume (mesh %s) | Blender / shatter (median wall, all cores) | Blender / shatter (1 thread) |" % info["mesh_volume"])
print("|---|---|---|---|---|---|---|")
for solver, rows in blender.items():
    med = statistics.median(s for s, _, _, _ in rows)
    print("| Blender Cell Fracture, %s | %s s (CPU %s s) | %.3f s | %s | %.6f | %.1f× | %.1f× |" % (
        solver, " / ".join("%.3f" % s for s, _, _, _ in rows), " / ".join("%.3f" % c for _, c, _, _ in rows),
        med, "/".join(sorted({str(n) for _, _, n, _ in rows})), rows[0][3], med * 1000 / sm, med * 1000 / sm1))
for label, runs, med in (("all cores", shatter, sm), ("1 thread (RAYON_NUM_THREADS=1)", shatter1, sm1)):
    print("| shatter voronoi, %s | %s ms | %.1f ms | %s | %.6f | | |" % (
        label, " / ".join("%.1f" % m for m, _, _ in runs), med, "/".join(sorted({str(f) for _, f, _ in runs})), runs[0][2]))
print("\nload averages (1 min) before each run: " + " ".join(loads))
PY
