#!/usr/bin/env bash
# Installs the Debian packages shellspace needs (when missing), configures a
# Release build in ./build and builds it. Usage: scripts/setup.sh [cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake libceres-dev libeigen3-dev libgoogle-glog-dev
          libgflags-dev libopenmesh-dev libgtest-dev libbenchmark-dev
          libsuitesparse-dev libpng-dev libopenblas-dev
          # glTF 2.0 export (io/gltf_writer.cc).
          libtinygltf-dev
          # The Python module (python/) and its tests (tests/python/).
          python3-dev pybind11-dev python3-numpy python3-scipy python3-pytest
          # shellspace.collections on a cluster (python/shellspace/collections.py).
          python3-distributed
          # pip install . (setup.py, pyproject.toml) and its test in a venv
          # (tests/python/pip_install_test.sh).
          python3-venv python3-pip python3-setuptools python3-wheel
          # The fuzz stage of scripts/test.sh: clang with libFuzzer and the
          # sanitizer runtimes; python3 writes the seed corpus.
          clang libclang-rt-dev python3)
# Node.js runs the Khronos glTF validator of the tests (ctest gltf_validator);
# Debian's packages unless a node is already installed.
command -v node >/dev/null || packages+=(nodejs npm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" ||
    missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

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

# The Python module is built for Debian's python3 (where pybind11-dev,
# numpy, scipy and pytest are installed), not for another python3 on PATH.
python_args=()
[ -x /usr/bin/python3 ] && python_args=(-DPython_EXECUTABLE=/usr/bin/python3)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${python_args[@]}" "$@" >/dev/null
cmake --build build -j"$(nproc)"
