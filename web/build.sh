#!/usr/bin/env bash
# Builds the web page: shatter-app compiled to wasm32-unknown-unknown (WebGL2), bound to
# JavaScript by wasm-bindgen, and web/index.html, all in web/dist/ — a static folder any
# static server can host (e.g. `python3 -m http.server -d web/dist`).
#
#   bash web/build.sh
#
# Installs what it lacks: the wasm32 target (rustup) and wasm-bindgen-cli at the exact
# version of the wasm-bindgen crate in Cargo.lock (cargo install; the two must match).
# Needs `wasm-opt` from binaryen 116 or newer; where it is missing or older it runs
# `cargo install wasm-opt --locked`, the crate that builds binaryen 116 from source (13 min
# on 2 cores, once). Debian 12's `binaryen` package is 108, whose -Oz output fails in the
# browser ("WebAssembly.Table.set(): Argument 1 is invalid for table": it breaks the
# externref table wasm-bindgen sets up). Needs `brotli` (Debian's `brotli`, which .ci/run
# installs) for the precompressed copies; gzip is everywhere.
#
# Output: index.html, shatter_app.js and shatter_app_bg.wasm, each with a `.gz` and a `.br`
# copy beside it (gzip -9, brotli -q 11) for servers that hand out precompressed files
# (see web/README.md, "Serving the compressed files").
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

opt_version=$(wasm-opt --version 2>/dev/null | awk '{print $3}' || true)
if ! [ "${opt_version:-0}" -ge 116 ] 2>/dev/null; then
    echo "build: wasm-opt ${opt_version:-missing} is older than binaryen 116: cargo install wasm-opt (builds binaryen, ~13 min)" >&2
    cargo install wasm-opt --locked
    export PATH="$HOME/.cargo/bin:$PATH"
fi
# -Oz: binaryen's size passes after LLVM's. The features are those rustc enables by default
# for wasm32-unknown-unknown, plus SIMD, which .cargo/config.toml turns on (every current
# browser has them all); wasm-opt must be told, or it refuses the module's bulk-memory,
# reference-types and SIMD instructions.
wasm=web/dist/shatter_app_bg.wasm
before=$(stat -c %s "$wasm")
wasm-opt -Oz --strip-debug --strip-producers \
    --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
    --enable-mutable-globals --enable-reference-types --enable-multivalue --enable-simd \
    -o "$wasm.opt" "$wasm"
mv "$wasm.opt" "$wasm"
echo "build: wasm-opt -Oz: $before -> $(stat -c %s "$wasm") bytes" >&2

command -v brotli >/dev/null || { echo "build: needs brotli (apt-get install brotli)" >&2; exit 1; }
for f in web/dist/index.html web/dist/shatter_app.js "$wasm"; do
    gzip -9 -k -f -n "$f"
    brotli -q 11 -k -f "$f"
done
ls -l web/dist
