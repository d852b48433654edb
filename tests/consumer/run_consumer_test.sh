#!/usr/bin/env bash
# Usage: tests/consumer/run_consumer_test.sh BUILD_DIR
#
# Proves the installed CMake package: installs the shellspace project from an
# already built BUILD_DIR into a temporary prefix, configures the consumer
# project next to this script against that prefix only (find_package through
# CMAKE_PREFIX_PATH), builds it in Release and runs it. Exits non-zero on any
# failure. The temporary directory is removed on exit.
set -euo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 BUILD_DIR" >&2
  exit 2
fi
build_dir="$(cd "$1" && pwd)"
consumer_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [[ ! -f "${build_dir}/cmake_install.cmake" ]]; then
  echo "$0: ${build_dir} is not a configured shellspace build directory" >&2
  exit 2
fi

work="$(mktemp -d "${TMPDIR:-/tmp}/shellspace-consumer.XXXXXX")"
trap 'rm -rf "${work}"' EXIT
prefix="${work}/prefix"
log="${work}/log"

# Runs a command quietly; prints its output if it fails.
quietly() {
  if ! "$@" >"${log}" 2>&1; then
    echo "$0: FAILED: $*" >&2
    cat "${log}" >&2
    exit 1
  fi
}

# Reads a variable from the build's CMake cache.
cached() {
  sed -n "s/^$1:[A-Z]*=//p" "${build_dir}/CMakeCache.txt"
}
# Use the compiler the library was built with (same C++ ABI), and the install
# layout it was configured with (GNUInstallDirs).
cxx="$(cached CMAKE_CXX_COMPILER)"
libdir="$(cached CMAKE_INSTALL_LIBDIR)"
bindir="$(cached CMAKE_INSTALL_BINDIR)"
includedir="$(cached CMAKE_INSTALL_INCLUDEDIR)"
libdir="${libdir:-lib}"
bindir="${bindir:-bin}"
includedir="${includedir:-include}"

quietly cmake --install "${build_dir}" --prefix "${prefix}"
package_dir="${prefix}/${libdir}/cmake/shellspace"
for installed in "${libdir}/libshellspace_cost_functions.a" "${bindir}/shellspace" \
    "${libdir}/cmake/shellspace/shellspaceConfig.cmake" \
    "${libdir}/cmake/shellspace/shellspaceConfigVersion.cmake" \
    "${libdir}/cmake/shellspace/shellspaceTargets.cmake" \
    "${includedir}/shellspace/cost_functions/deformation_energy_residuals.h" \
    "${includedir}/shellspace/cost_functions/shell/deformation_energy.h" \
    "${includedir}/shellspace/cost_functions/shell/element_set.h" \
    "${includedir}/shellspace/cost_functions/shell/shell_space.h" \
    "${includedir}/shellspace/cost_functions/membrane_cost_function.h"; do
  if [[ ! -f "${prefix}/${installed}" ]]; then
    echo "$0: FAILED: ${installed} was not installed" >&2
    exit 1
  fi
done
quietly "${prefix}/${bindir}/shellspace" --help

quietly cmake -S "${consumer_dir}" -B "${work}/build" \
  -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="${prefix}" \
  ${cxx:+-DCMAKE_CXX_COMPILER="${cxx}"}
# The package must have come from the temporary prefix, not from elsewhere.
found="$(sed -n 's/^shellspace_DIR:[A-Z]*=//p' "${work}/build/CMakeCache.txt")"
if [[ "${found}" != "${package_dir}" ]]; then
  echo "$0: FAILED: find_package(shellspace) used '${found}'," \
    "not ${package_dir}" >&2
  exit 1
fi
quietly cmake --build "${work}/build"
# Linking one room pulls in only the rooms below it and their dependencies
# (CHOLMOD comes with Ceres itself).
link_line="${work}/build/CMakeFiles/shellspace_consumer.dir/link.txt"
if [[ -f "${link_line}" ]] &&
   grep -qiE 'OpenMesh|libpng|umfpack|shellspace_(io|solvers|calculus|render)' "${link_line}"; then
  echo "$0: FAILED: the consumer of shellspace::cost_functions links more:" >&2
  cat "${link_line}" >&2
  exit 1
fi
"${work}/build/shellspace_consumer"
