#!/usr/bin/env bash
# Builds the web viewer (npm ci from web/package-lock.json: the npm registry is the only
# download) and runs its test in Debian's headless Chromium against a real kerf-server, with a
# cut made by kerf-haptic. Usage: viewer_test.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src=$1
bin=$2
cd "$src/web"
npm ci --no-audit --no-fund --loglevel=error
npm run --silent build
node test/viewer_test.mjs "$bin/server/kerf-server" "$bin/client/kerf-haptic"
