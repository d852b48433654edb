#!/usr/bin/env bash
# Installs the Debian packages of a profile (when missing), configures a
# Release build in ./build and builds it.
#   scripts/setup.sh [--profile cli|python|test] [--target T]... [--no-build]
#                    [cmake args]
# Profiles (each includes the one before it):
#   cli     the `shellspace` command: compiler, CMake, Ninja, Ceres, Eigen,
#           OpenMesh, gflags, glog, SuiteSparse, libpng, OpenBLAS, tinygltf;
#   python  the Python module, its tests and shellspace.collections on Dask;
#   test    everything scripts/test.sh runs: GoogleTest, Google Benchmark,
#           clang (fuzzers), Node.js with the Khronos glTF validator,
#           Chromium (the viewer's test). The default.
# --target builds only those targets (and what they link); --no-build stops
# after configuring. Phases are printed as "setup: <phase>".
set -euo pipefail
cd "$(dirname "$0")/.."

profile=test
targets=()
build=1
cmake_args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --profile) profile=${2:?--profile needs cli, python or test}; shift 2 ;;
    --profile=*) profile=${1#--profile=}; shift ;;
    --target) targets+=("${2:?--target needs a target}"); shift 2 ;;
    --no-build) build=0; shift ;;
    *) cmake_args+=("$1"); shift ;;
  esac
done

packages=(build-essential cmake ninja-build libceres-dev libeigen3-dev
          libgoogle-glog-dev libgflags-dev libopenmesh-dev
          libsuitesparse-dev libpng-dev libopenblas-dev
          # glTF 2.0 export (io/gltf_writer.cc).
          libtinygltf-dev)
case "$profile" in
  cli) ;;
  python|test)
    # The Python module (python/) and its tests (tests/python/);
    # shellspace.collections on a cluster (python/shellspace/collections/);
    # pip install . (setup.py, pyproject.toml) and its test in a venv
    # (tests/python/pip_install_test.sh).
    packages+=(python3 python3-dev pybind11-dev python3-numpy python3-scipy
               python3-pytest python3-distributed python3-venv python3-pip
               python3-setuptools python3-wheel)
    if [ "$profile" = test ]; then
      # The test suite and benchmarks; the fuzz stage of scripts/test.sh
      # (clang with libFuzzer and the sanitizer runtimes); the viewer's
      # test in headless Chromium (tests/tools/viewer_test.sh).
      packages+=(libgtest-dev libbenchmark-dev clang libclang-rt-dev chromium)
      # Node.js runs the Khronos glTF validator of the tests (ctest
      # gltf_validator); Debian's packages unless a node is already installed.
      command -v node >/dev/null || packages+=(nodejs npm)
    fi ;;
  *) echo "setup: unknown profile '$profile' (cli, python or test)" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" ||
    missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq \
    --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: the $profile packages are installed"
fi

if [ "$profile" = test ]; then
  # The Khronos glTF validator (npm package, pinned) in build/node, where
  # CMake's SHELLSPACE_GLTF_VALIDATOR_MODULES looks for it.
  validator_version=2.0.0-dev.3.10
  if [ ! -f build/node/node_modules/gltf-validator/package.json ] ||
     ! grep -q "\"version\": \"$validator_version\"" \
       build/node/node_modules/gltf-validator/package.json; then
    echo "setup: installing gltf-validator $validator_version (npm)"
    mkdir -p build/node
    npm install --no-save --no-audit --no-fund --prefix build/node \
      "gltf-validator@$validator_version" >/dev/null
  fi
fi

# The Python module is built for Debian's python3 (where pybind11-dev,
# numpy, scipy and pytest are installed), not for another python3 on PATH.
[ -x /usr/bin/python3 ] && cmake_args=(-DPython_EXECUTABLE=/usr/bin/python3 "${cmake_args[@]}")
[ "$profile" = cli ] && cmake_args=(-DSHELLSPACE_BUILD_PYTHON=OFF "${cmake_args[@]}")
# Ninja (it prints "[n/N]") unless build/ was configured with another
# generator already.
generator=()
if [ ! -f build/CMakeCache.txt ]; then
  generator=(-G Ninja)
fi
echo "setup: configuring build/ (Release)"
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${cmake_args[@]}" >/dev/null
[ "$build" = 1 ] || exit 0
echo "setup: building ${targets[*]:-everything} on $(nproc) cores"
scripts/build.sh build "${targets[@]}"
