#!/usr/bin/env bash
# Validates glTF/GLB files with the Khronos glTF-Validator.
#   scripts/validate_gltf.sh FILE...
# The validator (npm package gltf-validator) is installed on first use into
# $GLTF_VALIDATOR_DIR (default: build/tools/gltf-validator beside this script's
# repository). Exit status: 0 no errors, 1 a file has validation errors, 77 node/npm
# missing or the validator cannot be installed (a test treats that as "skip").
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="${GLTF_VALIDATOR_DIR:-$here/../build/tools/gltf-validator}"
if [[ $# -eq 0 ]]; then
  echo "usage: $0 FILE..." >&2
  exit 2
fi
if ! command -v node >/dev/null 2>&1; then
  echo "validate_gltf: node not found" >&2
  exit 77
fi
if [[ ! -f "$dir/node_modules/gltf-validator/package.json" ]]; then
  if ! command -v npm >/dev/null 2>&1; then
    echo "validate_gltf: npm not found (needed once to install gltf-validator)" >&2
    exit 77
  fi
  mkdir -p "$dir"
  if ! (cd "$dir" && npm install --no-audit --no-fund --loglevel=error gltf-validator >&2); then
    echo "validate_gltf: cannot install gltf-validator from the npm registry" >&2
    exit 77
  fi
fi
NODE_PATH="$dir/node_modules" exec node "$here/validate_gltf.js" "$@"
