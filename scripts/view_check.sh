#!/usr/bin/env bash
# Opens `mocapsolve view` pages in headless Chromium (Debian's chromium, driven by
# puppeteer-core) and checks or measures them: scripts/view_check.js does the work.
#   scripts/view_check.sh SPEC.json
# SPEC lists the pages and what to check on each (see view_check.js). Exit status: 0 every
# check passed, 1 a check failed, 77 chromium, node or puppeteer-core is unavailable (a
# test treats that as "skip"; MOCAPSOLVE_REQUIRE_DATA=1 makes the test fail instead).
# Chromium: $CHROMIUM, else chromium on the PATH.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [[ $# -ne 1 ]]; then
  echo "usage: $0 SPEC.json" >&2
  exit 2
fi
chromium="${CHROMIUM:-$(command -v chromium || command -v chromium-browser || true)}"
if [[ -z "$chromium" || ! -x "$chromium" ]]; then
  echo "view_check: chromium not found (apt-get install chromium; scripts/setup.sh installs it)" >&2
  exit 77
fi
tools="$("$here/viewer_tools.sh")" || exit $?
CHROMIUM="$chromium" NODE_PATH="$tools/node_modules" exec node "$here/view_check.js" "$1"
