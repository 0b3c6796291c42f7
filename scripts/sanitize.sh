#!/usr/bin/env bash
# Builds the whole project with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DMOCAPSOLVE_SANITIZE=ON, RelWithDebInfo) in build-asan/ and runs the suite
# there; prints the build and test wall times. Extra arguments go to ctest (e.g. -R Bvh).
# Leaks inside Debian's uninstrumented assimp/zlib are suppressed as for fuzzing
# (fuzz/lsan.supp); UBSan findings fail the test that hits them.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [ ! -f build-asan/CMakeCache.txt ]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMOCAPSOLVE_SANITIZE=ON \
    -DMOCAPSOLVE_BUILD_BENCHMARKS=OFF "${launcher[@]}" >/dev/null
fi
start=$(date +%s)
echo "sanitize.sh: building build-asan/ (log in build-asan/build.log)"
if ! nice cmake --build build-asan -j2 >build-asan/build.log 2>&1; then
  grep -E 'error' build-asan/build.log | head -20 >&2
  exit 1
fi
built=$(date +%s)
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export ASAN_OPTIONS="detect_leaks=1"
set +e
(cd build-asan && ctest --output-on-failure -j2 --timeout 1800 "$@")
rc=$?
set -e
done_at=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, tests $((done_at - built)) s, ctest exit $rc"
exit $rc
