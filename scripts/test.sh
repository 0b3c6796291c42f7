#!/usr/bin/env bash
# Builds everything and runs the whole suite through ctest.
# Real-data tests read MOCAPSOLVE_DATA (default ../shared/data) and skip without it;
# with MOCAPSOLVE_REQUIRE_DATA=1 (as CI sets) a missing file fails instead.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup.sh
cd build
ctest --output-on-failure -j2 --timeout 600
