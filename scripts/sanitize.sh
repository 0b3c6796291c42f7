#!/usr/bin/env bash
# Builds the project with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DMOCAPSOLVE_SANITIZE=ON) in build-asan/ and runs the suite there; prints the build and
# test wall times. .ci/run runs it after the Release suite.
#   scripts/sanitize.sh [--only=FOLDERS] [--layers=LAYERS] [extra ctest arguments, e.g. -R Bvh]
# --only=io,apps builds the CLI and only the tests of those tests/ folders (CMake targets
# tests_io, tests_apps) and runs the tests labelled with them.
# --layers=io,tasks,... instruments only those library layers (MOCAPSOLVE_SANITIZE_LAYERS; the
# CLI is always instrumented); the others compile with the Release flags, so ccache serves
# them from build/. Without it (or with --layers=all) every layer is instrumented.
# The build is made cheap, since it only has to find faults: the code under test (library,
# CLI) is instrumented at -O1 with line tables only (-g1: sanitizer reports keep file:line,
# without full debug info, which dominated compile and link time); the test files are not
# instrumented and compile with the Release flags, so that ccache serves them from the
# Release build (CMakeLists.txt, mocapsolve_instrument); no benchmarks (so no peers) and no
# Python module.
# Executables are linked without PIE: a position-independent ASan build of the CLI carries
# ~100 MB of relocations that the loader applies at every start (3.0 s per process here,
# 0.5 s without), and the CLI tests start it thousands of times.
# Leaks inside Debian's uninstrumented assimp/zlib are suppressed as for fuzzing
# (fuzz/lsan.supp); UBSan findings fail the test that hits them.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
only=""
layers=all
while [ $# -gt 0 ]; do
  case "$1" in
    --only=*) only=${1#--only=} ;;
    --layers=*) layers=${1#--layers=} ;;
    *) break ;;
  esac
  shift
done
[ "$layers" = all ] && layers=""
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [ ! -f build-asan/CMakeCache.txt ]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXE_LINKER_FLAGS=-no-pie \
    -DMOCAPSOLVE_SANITIZE=ON -DMOCAPSOLVE_BUILD_BENCHMARKS=OFF -DMOCAPSOLVE_PYTHON=OFF "${launcher[@]}" >/dev/null
fi
cmake -S . -B build-asan "-DMOCAPSOLVE_SANITIZE_LAYERS=${layers//,/;}" >/dev/null
targets=()
labels=()
if [ -n "$only" ]; then
  targets=(--target mocapsolve_cli)
  for folder in ${only//,/ }; do
    targets+=("tests_$folder")
    labels+=("$folder")
  done
fi
start=$(date +%s)
echo "sanitize.sh: building build-asan/ ${only:+(tests of $only only) }${layers:+(instrumented layers: $layers) }(log in build-asan/build.log; load $(cut -d' ' -f1-3 /proc/loadavg))"
if ! nice cmake --build build-asan -j2 "${targets[@]}" >build-asan/build.log 2>&1; then
  grep -E 'error' build-asan/build.log | head -20 >&2
  exit 1
fi
built=$(date +%s)
# The viewer's npm runtime is installed once, in the Release build's folder (setup.sh).
if [ -z "${MOCAPSOLVE_VIEWER_TOOLS:-}" ] && [ -d build/tools/viewer ]; then
  export MOCAPSOLVE_VIEWER_TOOLS=$PWD/build/tools/viewer
fi
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export ASAN_OPTIONS="detect_leaks=1"
select=()
if [ ${#labels[@]} -gt 0 ]; then
  pattern=$(IFS='|'; echo "${labels[*]}")
  select=(-L "^($pattern)\$")
fi
set +e
(cd build-asan && ctest --output-on-failure -j2 --timeout 1800 "${select[@]}" "$@")
rc=$?
set -e
done_at=$(date +%s)
echo "sanitize.sh: build $((built - start)) s, tests $((done_at - built)) s, ctest exit $rc (load $(cut -d' ' -f1-3 /proc/loadavg))"
exit $rc
