#!/usr/bin/env bash
# Builds the Blender add-on zip: bash blender/package.sh [OUT.zip]
# (default blender/dist/shatter_fracture.zip). Install it in Blender with
# Edit > Preferences > Add-ons > Install... and tick "Object: Shatter Fracture".
# The zip holds the folder shatter_fracture/ with its .py files only (no caches).
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${1:-$HERE/dist/shatter_fracture.zip}
mkdir -p "$(dirname "$OUT")"
python3 - "$HERE" "$OUT" <<'PY'
import os, sys, zipfile
here, out = sys.argv[1], sys.argv[2]
src = os.path.join(here, "shatter_fracture")
names = sorted(n for n in os.listdir(src) if n.endswith(".py"))
if "__init__.py" not in names:
    sys.exit("error: %s has no __init__.py" % src)
tmp = out + ".tmp"
with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
    for n in names:
        # A fixed timestamp: the same sources give the same zip.
        info = zipfile.ZipInfo("shatter_fracture/" + n, date_time=(2026, 1, 1, 0, 0, 0))
        info.external_attr = 0o644 << 16
        info.compress_type = zipfile.ZIP_DEFLATED
        with open(os.path.join(src, n), "rb") as f:
            z.writestr(info, f.read())
os.replace(tmp, out)
print("wrote %s (%d files)" % (out, len(names)))
PY
