#!/usr/bin/env bash
# Builds everything, then serves the page on 127.0.0.1 (default port 8080; PORT=… to change).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
exec node scripts/serve.mjs build/wasm/site "${PORT:-8080}"
