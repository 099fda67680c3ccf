#!/usr/bin/env bash
# Builds the web page: shatter-app compiled to wasm32-unknown-unknown (WebGL2), bound to
# JavaScript by wasm-bindgen, and web/index.html, all in web/dist/ — a static folder any
# static server can host (e.g. `python3 -m http.server -d web/dist`).
#
#   bash web/build.sh
#
# Installs what it lacks: the wasm32 target (rustup) and wasm-bindgen-cli at the exact
# version of the wasm-bindgen crate in Cargo.lock (cargo install; the two must match).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$HOME/.cache/shatter-target}"

if command -v rustup >/dev/null && ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    echo "build: rustup target add wasm32-unknown-unknown" >&2
    rustup target add wasm32-unknown-unknown
fi

version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' Cargo.lock)
if [ -z "$version" ]; then
    echo "build: no wasm-bindgen in Cargo.lock" >&2
    exit 1
fi
if ! command -v wasm-bindgen >/dev/null || [ "$(wasm-bindgen --version | awk '{print $2}')" != "$version" ]; then
    echo "build: cargo install wasm-bindgen-cli $version" >&2
    # --locked first (the crate's own lock file); that lock can name a release the registry
    # no longer serves, so fall back to a fresh resolution of the same version.
    cargo install wasm-bindgen-cli --version "$version" --locked ||
        cargo install wasm-bindgen-cli --version "$version"
fi

cargo build --locked --profile web --target wasm32-unknown-unknown -p shatter-app --bin shatter-app

rm -rf web/dist
mkdir -p web/dist
# The name section (function names for stack traces) is a third of the file: drop it.
wasm-bindgen --target web --no-typescript --remove-name-section --remove-producers-section \
    --out-name shatter_app --out-dir web/dist \
    "$CARGO_TARGET_DIR/wasm32-unknown-unknown/web/shatter-app.wasm"
cp web/index.html web/dist/
ls -l web/dist
