#!/usr/bin/env bash
# Shared set-up for scripts/demo.sh and scripts/test.sh: install what is missing from
# Debian 12's packages (as root), configure a Release build in build/ and build it.
# Idempotent: a second run installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

packages=(build-essential cmake pkg-config libeigen3-dev libceres-dev libsuitesparse-dev
          libgoogle-glog-dev libgflags-dev libgtest-dev libgmock-dev libbenchmark-dev
          libtinygltf-dev libassimp-dev libnanoflann-dev libspectra-dev zlib1g-dev
          python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest
          python3-matplotlib python3-jsonschema python3-setuptools python3-venv python3-pip chromium ccache)
# node and npm (for scripts/viewer_tools.sh and validate_gltf.sh) are taken as found: this
# machine's come from NodeSource, whose nodejs bundles npm and conflicts with Debian's npm.
# Opt-in: `setup.sh --fuzz` also installs what scripts/fuzz.sh needs (clang, libFuzzer)
# and then only installs (the fuzz build is scripts/fuzz.sh's own, in build-fuzz/).
fuzz_packages=(clang libclang-rt-14-dev libfuzzer-14-dev)
# Opt-in: `setup.sh --with-peers` also installs the peer kinematics libraries of the peers
# benchmark (bench/peers: Orocos KDL, MuJoCo, DART; about 600 MB with DART's dependencies),
# then reconfigures and builds as usual, so build/bin/mocapsolve_peers_bench appears.
# Not in the default list: CI stays lean, and the build never requires them.
peer_packages=(liborocos-kdl-dev libmujoco-dev libdart-dev)
# Opt-in: `setup.sh --with-blender` also installs Debian's Blender (3.4, about 700 MB with
# its libraries) for the FBX import check (tests/python/test_fbx_blender.py: every FBX the
# pipeline writes imported headless; without Blender it skips, or fails when real data is
# required, as CI requires it), then builds as usual.
blender_packages=(blender)
only_install=0
reconfigure=0
for option in "$@"; do
  case "$option" in
    --fuzz) packages+=("${fuzz_packages[@]}"); only_install=1 ;;
    --with-peers) packages+=("${peer_packages[@]}"); reconfigure=1 ;;
    --with-blender) packages+=("${blender_packages[@]}") ;;
    *) echo "setup: unknown option '$option' (known: --fuzz, --with-peers, --with-blender)" >&2; exit 1 ;;
  esac
done
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: missing packages (${missing[*]}); run as root or apt-get install them" >&2
    exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

[ "$only_install" -eq 0 ] || exit 0

build_type=${MOCAPSOLVE_BUILD_TYPE:-Release}
launcher=()  # ccache when present, as sanitize.sh and fuzz.sh use it: rebuilds of clones are quick
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE="$build_type" "${launcher[@]}" ${MOCAPSOLVE_CMAKE_ARGS:-} >/dev/null
elif [ "$reconfigure" -eq 1 ]; then
  cmake -S . -B build >/dev/null  # Finds the peer libraries an earlier configure lacked.
fi
echo "setup: building (build/, $build_type; log in build/build.log)"
if ! cmake --build build -j2 >build/build.log 2>&1; then
  grep -E 'error|Error' build/build.log | head -40 >&2
  echo "setup: build failed (full log: build/build.log)" >&2
  exit 1
fi
grep -i 'warning' build/build.log | head -20 || true
# The viewer's runtime (three.js bundle) and its browser test's driver, from npm into
# build/tools/viewer. Without network `mocapsolve view` says how to retry, and the browser
# tests skip.
# The viewer's pages are promised outputs of `pipeline` and `view`: without the runtime,
# setup stops here and says what to run (MOCAPSOLVE_NO_VIEWER=1 builds without it).
if [ "${MOCAPSOLVE_NO_VIEWER:-0}" != 1 ] && ! scripts/viewer_tools.sh >/dev/null; then
  echo "setup: the viewer's npm packages could not be installed; check the network to the npm" \
       "registry and run scripts/viewer_tools.sh, then this script again (or set MOCAPSOLVE_NO_VIEWER=1" \
       "to build and test without the viewer: its pages and browser tests are then skipped)" >&2
  exit 1
fi
