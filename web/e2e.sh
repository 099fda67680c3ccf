#!/usr/bin/env bash
# Browser end-to-end test of the shatter web build (see README.md).
#   bash web/e2e.sh [screenshot.png]
# SKIP_BUILD=1 skips `bash build.sh` (test an existing web/dist).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")"

if [ ! -x /usr/bin/chromium ]; then
  echo "e2e: installing chromium (Debian package)" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update
  apt-get install -y chromium
fi

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  echo "e2e: needs Node.js >= 20 and npm (playwright-core requires Node 20)" >&2
  exit 1
fi

if [ ! -d node_modules/playwright-core ]; then
  echo "e2e: npm ci" >&2
  npm ci --no-audit --no-fund
fi

if [ -z "${SKIP_BUILD:-}" ]; then
  bash build.sh
fi

exec node e2e.mjs "$@"
