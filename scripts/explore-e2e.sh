#!/usr/bin/env bash
# The explorer as a person uses it: Debian's Chromium, driven by
# playwright-core from npm, walks through the page (tests/explore/e2e.mjs)
# and saves a screenshot in tests/explore/output/.
#
#   IMPACT=target/release/impact scripts/explore-e2e.sh [OUTPUT_DIR]
#
# Installs chromium from Debian when missing (as root; otherwise it says
# why and skips) and playwright-core with `npm ci` from the lock file.
set -euo pipefail
cd "$(dirname "$0")/.."
IMPACT=${IMPACT:-target/release/impact}
if [ ! -x "$IMPACT" ]; then
  echo "no binary at $IMPACT: build it (cargo build --release) or set IMPACT" >&2
  exit 1
fi
if ! command -v chromium >/dev/null 2>&1; then
  if [ "$(id -u)" != 0 ]; then
    echo "skipped: chromium is not installed and installing it needs root (apt-get install chromium)"
    exit 0
  fi
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
fi
if ! command -v node >/dev/null 2>&1; then
  echo "node not found: install Node.js (Debian: apt-get install nodejs npm)" >&2
  exit 1
fi
(cd tests/explore && npm ci --no-audit --no-fund --silent)
IMPACT="$(realpath "$IMPACT")" node tests/explore/e2e.mjs "$@"
