#!/usr/bin/env bash
# The add-on's tests: plain-Python unit tests of its runner (no Blender), then the
# headless Blender test (test_addon.py) on the packaged zip, as a user installs it.
#
# usage: bash blender/tests/run.sh [SHATTER]
#   SHATTER: the shatter binary (default $SHATTER, else $CARGO_TARGET_DIR/debug/shatter,
#   which `cargo test --workspace` builds). Needs Debian's blender and python3-numpy
#   (.ci/run installs them). Blender's user scripts and config go to a temporary folder,
#   never to ~/.config/blender.
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
TARGET=${CARGO_TARGET_DIR:-$HOME/.cache/shatter-target}
SHATTER=${1:-${SHATTER:-$TARGET/debug/shatter}}
command -v blender >/dev/null || { echo "error: blender not on PATH (apt-get install blender python3-numpy)" >&2; exit 1; }
[[ -x $SHATTER ]] || { echo "error: no shatter binary at $SHATTER (cargo build -p shatter-cli)" >&2; exit 1; }
SHATTER=$(cd "$(dirname "$SHATTER")" && pwd)/$(basename "$SHATTER")

WORK=$(mktemp -d "${TMPDIR:-/tmp}/shatter-blender-test.XXXXXX")
LOG=${TMPDIR:-/tmp}/shatter-blender-test.log  # Blender's whole output, kept
trap 'rm -rf "$WORK"' EXIT
python3 "$HERE/test_runner.py"
bash "$ROOT/blender/package.sh" "$WORK/shatter_fracture.zip"
echo "# $(blender --version 2>/dev/null | head -1); $("$SHATTER" --version)"
BLENDER_USER_SCRIPTS="$WORK/scripts" BLENDER_USER_CONFIG="$WORK/config" \
  blender -b --factory-startup --python-exit-code 1 --python "$HERE/test_addon.py" \
  -- "$WORK/shatter_fracture.zip" "$SHATTER" > "$LOG" 2>&1 || {
    grep -E '^(FAIL|SKIP)|Error|Traceback|blender-addon:' "$LOG" | tail -80 >&2
    echo "error: the Blender add-on test failed (Blender's whole output: $LOG)" >&2
    exit 1
  }
grep -E '^(FAIL|SKIP)' "$LOG" || true
grep -E '^blender-addon:' "$LOG"
