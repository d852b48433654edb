#!/usr/bin/env bash
# Installs the Debian packages shellspace needs (when missing), configures a
# Release build in ./build and builds it. Usage: scripts/setup.sh [cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake libceres-dev libeigen3-dev libgoogle-glog-dev
          libgflags-dev libopenmesh-dev libgtest-dev libbenchmark-dev
          libsuitesparse-dev libpng-dev libopenblas-dev
          # The fuzz stage of scripts/test.sh: clang with libFuzzer and the
          # sanitizer runtimes; python3 writes the seed corpus.
          clang libclang-rt-dev python3)
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

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build build -j"$(nproc)"
