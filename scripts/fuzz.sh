#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang + ASan + UBSan) in build-fuzz/ and runs them.
#   scripts/fuzz.sh [TARGET] [--runs=N | --seconds=S] [-- extra libFuzzer flags]
# TARGET: bvh, asf, amc, c3d, trc, json, gltf, fbx, manifest, or all (default). Default budget:
# --seconds=120 per target. Opt-in: needs clang and libFuzzer (scripts/setup.sh
# --fuzz installs them). Each target keeps a growing corpus in build-fuzz/corpus/TARGET
# (seeded by fuzz/make_seeds.py and by tests/data/bad's files of its format) and writes
# crashes, leaks, timeouts and OOMs to build-fuzz/artifacts/TARGET/. Runs under nice -n 19
# (the machine is shared). The last line per target:
# "fuzz TARGET: N runs in S s (E exec/s), cov C, ft F, corpus K, found: ..."
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

all=(bvh asf amc c3d trc json gltf fbx manifest)
targets=()
budget=(-max_total_time=120)
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --runs=*) budget=(-runs="${1#--runs=}") ;;
    --seconds=*) budget=(-max_total_time="${1#--seconds=}") ;;
    --) shift; extra=("$@"); break ;;
    all) targets=("${all[@]}") ;;
    *)
      if [[ " ${all[*]} " == *" $1 "* ]]; then targets+=("$1"); else
        echo "fuzz.sh: unknown argument '$1' (targets: ${all[*]} all; --runs=N, --seconds=S)" >&2
        exit 2
      fi ;;
  esac
  shift
done
[ ${#targets[@]} -gt 0 ] || targets=("${all[@]}")

if ! command -v clang++ >/dev/null || ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  echo "fuzz.sh: needs clang and libFuzzer: run scripts/setup.sh --fuzz (as root)" >&2
  exit 1
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [ ! -f build-fuzz/CMakeCache.txt ]; then
  CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMOCAPSOLVE_FUZZ=ON \
    -DMOCAPSOLVE_BUILD_TESTS=OFF -DMOCAPSOLVE_BUILD_BENCHMARKS=OFF "${launcher[@]}" >/dev/null
fi
echo "fuzz.sh: building ${targets[*]} (build-fuzz/; log in build-fuzz/build.log)"
if ! nice cmake --build build-fuzz -j2 --target "${targets[@]/%/_fuzzer}" >build-fuzz/build.log 2>&1; then
  grep -E 'error' build-fuzz/build.log | head -20 >&2
  exit 1
fi
/usr/bin/python3 fuzz/make_seeds.py build-fuzz/seeds
# tests/data/bad's files join the seeds of the target that reads their format.
rm -rf build-fuzz/bad
for t in "${all[@]}"; do
  mkdir -p "build-fuzz/bad/$t"
  case "$t" in
    gltf) patterns=(bad_*.gltf bad_*.glb) ;;
    manifest) patterns=(bad_manifest_*.json) ;;
    *) patterns=("bad_*.$t") ;;
  esac
  for p in "${patterns[@]}"; do
    for f in tests/data/bad/$p; do
      if [ -e "$f" ]; then cp "$f" "build-fuzz/bad/$t/"; fi
    done
  done
done

# Leaks inside Debian's uninstrumented assimp/zlib are suppressed by name (fuzz/lsan.supp).
export LSAN_OPTIONS="suppressions=$PWD/fuzz/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/artifacts/$t"
  log="build-fuzz/fuzz-$t.log"
  start=$(date +%s)
  set +e
  nice -n 19 "build-fuzz/bin/${t}_fuzzer" "build-fuzz/corpus/$t" "build-fuzz/seeds/$t" "build-fuzz/bad/$t" \
    "${budget[@]}" -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/artifacts/$t/" "${extra[@]}" >"$log" 2>&1
  rc=$?
  set -e
  seconds=$(( $(date +%s) - start ))
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
  speed=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(echo "$last" | grep -o 'cov: [0-9]*' | grep -o '[0-9]*' || echo '?')
  ft=$(echo "$last" | grep -o 'ft: [0-9]*' | grep -o '[0-9]*' || echo '?')
  corpus=$(echo "$last" | grep -o 'corp: [0-9]*' | grep -o '[0-9]*' || echo '?')
  found=$(ls "build-fuzz/artifacts/$t" | tr '\n' ' ')
  [ $rc -eq 0 ] || status=1
  echo "fuzz $t: $runs runs in $seconds s ($speed exec/s), cov $cov, ft $ft, corpus $corpus, exit $rc, found: ${found:-nothing}"
done
exit $status
