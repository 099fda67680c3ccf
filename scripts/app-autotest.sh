#!/usr/bin/env bash
# Runs shatter-app's scripted session (--autotest) in a virtual X display with Mesa's
# software renderer, and checks its results (crates/shatter-app/tests/autotest.rs).
#
# Needs Debian packages: xvfb xauth mesa-vulkan-drivers libgl1-mesa-dri
# Usage: scripts/app-autotest.sh [OUT_DIR]   (default: target/app-autotest)
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v xvfb-run >/dev/null; then
    echo "xvfb-run not found: apt-get install -y xvfb xauth mesa-vulkan-drivers libgl1-mesa-dri" >&2
    exit 2
fi

out="${1:-target/app-autotest}"
mkdir -p "$out"
export SHATTER_APP_AUTOTEST_DIR
SHATTER_APP_AUTOTEST_DIR="$(cd "$out" && pwd)"
# Quiet the renderer's per-frame logs; keep warnings and the app's own messages.
export RUST_LOG="${RUST_LOG:-warn,shatter_app=info}"

xvfb-run -a -s "-screen 0 1280x800x24" \
    cargo test -p shatter-app --test autotest -- --ignored --nocapture
echo "screenshots and state.json in $SHATTER_APP_AUTOTEST_DIR"
