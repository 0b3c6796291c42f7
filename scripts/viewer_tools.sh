#!/usr/bin/env bash
# Installs what `mocapsolve view` and its browser test need, from npm, into
# $MOCAPSOLVE_VIEWER_TOOLS (default: build/tools/viewer beside this script's repository):
#   three (the renderer), esbuild (bundles three + its OrbitControls and GLTFLoader into
#   one classic script, three.bundle.js, that `view` inlines into every page), and
#   puppeteer-core (drives Debian's chromium in the browser test and benchmark).
# Versions are pinned here. Idempotent: a second run installs nothing.
#   scripts/viewer_tools.sh          install (exit 0), or 77 if node/npm are missing or the
#                                    registry cannot be reached after MOCAPSOLVE_NPM_ATTEMPTS
#                                    tries with backoff (default 5; a test treats 77 as "skip")
#   scripts/viewer_tools.sh --bundle only the bundle (three + esbuild), no puppeteer-core
# Prints the tools folder on stdout.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="${MOCAPSOLVE_VIEWER_TOOLS:-$here/../build/tools/viewer}"
three_version=0.170.0
esbuild_version=0.24.0
puppeteer_version=23.11.1
packages=("three@$three_version" "esbuild@$esbuild_version")
[[ "${1:-}" == "--bundle" ]] || packages+=("puppeteer-core@$puppeteer_version")

if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  echo "viewer_tools: node/npm not found (apt-get install nodejs npm)" >&2
  exit 77
fi
mkdir -p "$dir"
dir="$(cd "$dir" && pwd)"
missing=()
for p in "${packages[@]}"; do
  name="${p%@*}" version="${p##*@}"
  installed="$(node -p "try{require('$dir/node_modules/$name/package.json').version}catch(e){''}" 2>/dev/null)"
  [[ "$installed" == "$version" ]] || missing+=("$p")
done
if [[ ${#missing[@]} -gt 0 ]]; then
  [[ -f "$dir/package.json" ]] || echo '{"name": "mocapsolve-viewer-tools", "private": true}' > "$dir/package.json"
  # A registry error is often transient (ECONNRESET, ETIMEDOUT): retry with backoff.
  attempt=1
  until (cd "$dir" && npm install --no-audit --no-fund --loglevel=error --save-exact "${missing[@]}" >&2); do
    if [[ $attempt -ge ${MOCAPSOLVE_NPM_ATTEMPTS:-5} ]]; then
      echo "viewer_tools: cannot install ${missing[*]} from the npm registry after $attempt attempts" >&2
      exit 77
    fi
    echo "viewer_tools: npm install failed (attempt $attempt); retrying in $((attempt * 5)) s" >&2
    sleep $((attempt * 5))
    attempt=$((attempt + 1))
  done
  rm -f "$dir/three.bundle.js"
fi
bundle="$dir/three.bundle.js"
if [[ ! -s "$bundle" || "$here/../viewer/three_entry.js" -nt "$bundle" ]]; then
  # The entry is copied beside node_modules so that 'three' resolves there.
  cp "$here/../viewer/three_entry.js" "$dir/three_entry.js"
  if ! (cd "$dir" && ./node_modules/.bin/esbuild three_entry.js --bundle --minify \
          --format=iife --global-name=MOCAPSOLVE_THREE --legal-comments=none \
          --log-level=warning --outfile="$bundle.tmp" >&2); then
    echo "viewer_tools: esbuild could not bundle three.js" >&2
    exit 77
  fi
  mv "$bundle.tmp" "$bundle"
fi
echo "$dir"
