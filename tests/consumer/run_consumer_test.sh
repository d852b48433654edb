#!/usr/bin/env bash
# Usage: tests/consumer/run_consumer_test.sh BUILD_DIR
#
# Proves the installed CMake package installs anywhere: installs the
# shellspace project from an already built BUILD_DIR into a temporary
# prefix, moves the prefix to another path, then
#   - fails if a package file names a path of the machine (the first prefix,
#     the build or source tree, any absolute path) or an installed header
#     includes a project header other than as "shellspace/...";
#   - configures the consumer project next to this script against the moved
#     prefix only (find_package through CMAKE_PREFIX_PATH) with COMPONENTS
#     cost_functions and find_package of OpenMesh, PNG and TinyGLTF disabled,
#     builds it in Release and runs it (main.cc), checking its link line
#     (no room above, OpenBLAS first), that it did not look for CHOLMOD or
#     UMFPACK and that only <prefix>/include is on its include path;
#   - does the same for the consumer of every room (whole.cc,
#     -DSHELLSPACE_CONSUMER_WHOLE=ON);
#   - checks that an unknown component is an error naming it.
# Exits non-zero on any failure. The temporary directory is removed on exit.
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

first_prefix="${work}/installed"
quietly cmake --install "${build_dir}" --prefix "${first_prefix}"
mkdir -p "${work}/moved"
prefix="${work}/moved/elsewhere"
mv "${first_prefix}" "${prefix}"
package_dir="${prefix}/${libdir}/cmake/shellspace"
for installed in "${libdir}/libshellspace_cost_functions.a" "${bindir}/shellspace" \
    "${libdir}/cmake/shellspace/shellspaceConfig.cmake" \
    "${libdir}/cmake/shellspace/shellspaceConfigVersion.cmake" \
    "${libdir}/cmake/shellspace/shellspaceSystemLibraries.cmake" \
    "${libdir}/cmake/shellspace/shellspaceTargets.cmake" \
    "${libdir}/cmake/shellspace/shellspace_cost_functionsTargets.cmake" \
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

# No package file names a path of this machine: neither the prefix it was
# installed into, nor the build or source tree, nor any absolute path (a
# quoted or listed word starting with /; the targets files compute their
# prefix from their own location).
source_dir="$(cached CMAKE_HOME_DIRECTORY)"
for path in "${first_prefix}" "${build_dir}" "${source_dir}"; do
  if grep -rnF -- "${path}" "${package_dir}" >"${log}"; then
    echo "$0: FAILED: the installed package names ${path}:" >&2
    cat "${log}" >&2
    exit 1
  fi
done
if grep -rnE '(^|[";=[:space:]])/[A-Za-z0-9_.]' "${package_dir}" >"${log}"; then
  echo "$0: FAILED: the installed package names an absolute path:" >&2
  cat "${log}" >&2
  exit 1
fi
# The installed headers reach each other as "shellspace/<room>/...", so
# <prefix>/include alone is enough.
if grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' \
    "${prefix}/${includedir}/shellspace" | grep -vE '#[[:space:]]*include[[:space:]]*"shellspace/' >"${log}"; then
  echo "$0: FAILED: an installed header includes a project header" \
    "other than as \"shellspace/...\":" >&2
  cat "${log}" >&2
  exit 1
fi

# Configures the consumer into ${work}/$1 against the moved prefix only,
# with the further arguments (Unix Makefiles: the checks read its link.txt).
configure_consumer() {
  local name="$1"
  shift
  quietly cmake -S "${consumer_dir}" -B "${work}/${name}" \
    -G "Unix Makefiles" \
    -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="${prefix}" \
    -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
    ${cxx:+-DCMAKE_CXX_COMPILER="${cxx}"} "$@"
  # The package must have come from the moved prefix, not from elsewhere.
  local found
  found="$(sed -n 's/^shellspace_DIR:[A-Z]*=//p' "${work}/${name}/CMakeCache.txt")"
  if [[ "${found}" != "${package_dir}" ]]; then
    echo "$0: FAILED: find_package(shellspace) used '${found}'," \
      "not ${package_dir}" >&2
    exit 1
  fi
}

# Builds the consumer configured into ${work}/$1 and checks how it was
# compiled and linked: <prefix>/include on the include path, not
# <prefix>/include/shellspace (headers reached as <shellspace/...> only), and,
# if the consumer found OpenBLAS, that library linked ahead of everything
# (before the objects on the link line; tests/blas_order_test.sh says why).
# Sets link_line to the file of its link command.
build_consumer() {
  local name="$1" program="$2"
  quietly cmake --build "${work}/${name}"
  local commands="${work}/${name}/compile_commands.json"
  if ! grep -qF -- "${prefix}/${includedir}" "${commands}" ||
     grep -qF -- "${prefix}/${includedir}/shellspace" "${commands}"; then
    echo "$0: FAILED: the ${name} consumer's include path is not" \
      "${prefix}/${includedir} alone:" >&2
    cat "${commands}" >&2
    exit 1
  fi
  link_line="${work}/${name}/CMakeFiles/${program}.dir/link.txt"
  if [[ ! -f "${link_line}" ]]; then
    echo "$0: FAILED: no ${link_line}" >&2
    exit 1
  fi
  local blas
  blas="$(sed -n 's/^SHELLSPACE_FAST_BLAS:[A-Z]*=//p' "${work}/${name}/CMakeCache.txt")"
  if [[ -n "${blas}" && "${blas}" != *NOTFOUND ]] &&
     ! grep -qF -- "-Wl,--no-as-needed ${blas} -Wl,--as-needed CMakeFiles/" "${link_line}"; then
    echo "$0: FAILED: the ${name} consumer does not link ${blas} first:" >&2
    cat "${link_line}" >&2
    exit 1
  fi
}

# The consumer of the cost functions alone: the package finds neither the
# private dependencies of the rooms it does not load (their find_package is
# disabled) nor CHOLMOD or UMFPACK.
configure_consumer cost_functions \
  -DCMAKE_DISABLE_FIND_PACKAGE_OpenMesh=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_TinyGLTF=ON
if grep -E '^SHELLSPACE_(CHOLMOD|UMFPACK)' "${work}/cost_functions/CMakeCache.txt" >"${log}"; then
  echo "$0: FAILED: find_package(shellspace COMPONENTS cost_functions)" \
    "looked for CHOLMOD or UMFPACK:" >&2
  cat "${log}" >&2
  exit 1
fi
build_consumer cost_functions shellspace_consumer
# Linking one room pulls in only the rooms below it and their dependencies
# (CHOLMOD comes with Ceres itself).
if grep -qiE 'OpenMesh|libpng|tinygltf|umfpack|shellspace_(io|solvers|calculus|render)' "${link_line}"; then
  echo "$0: FAILED: the consumer of shellspace::cost_functions links more:" >&2
  cat "${link_line}" >&2
  exit 1
fi
"${work}/cost_functions/shellspace_consumer"

# The consumer of every room: io, calculus and solvers, PNG and glTF.
configure_consumer whole -DSHELLSPACE_CONSUMER_WHOLE=ON
build_consumer whole shellspace_consumer_whole
"${work}/whole/shellspace_consumer_whole" "${work}/whole"

# An unknown component is an error that names it.
if cmake -S "${consumer_dir}" -B "${work}/unknown" \
    -DCMAKE_PREFIX_PATH="${prefix}" \
    -DSHELLSPACE_CONSUMER_COMPONENTS="io;no_such_room" >"${log}" 2>&1; then
  echo "$0: FAILED: find_package(shellspace COMPONENTS io no_such_room)" \
    "succeeded" >&2
  exit 1
fi
if ! grep -q "unknown component 'no_such_room'" "${log}"; then
  echo "$0: FAILED: the error of an unknown component does not name it:" >&2
  cat "${log}" >&2
  exit 1
fi
