#!/usr/bin/env bash
# A second stress corpus, of public meshes the first one (../shared/data/cgal)
# does not contain: the example meshes Debian ships in the package
# libcgal-demo (usr/share/doc/libcgal-dev/data.tar.gz, data/meshes/).
# Downloads the package with `apt-get download` (no installation, no root),
# unpacks the chosen meshes and runs bench/stress_corpus.sh on them with the
# same environment variables (CORPUS_DEFORMATIONS, CORPUS_VERBS, CORPUS_CAP,
# CORPUS_SEED); the table goes to standard output.
#
# Usage: bench/debian_meshes.sh [BUILD_DIR] [OUT_DIR]
# Environment:
#   DEBIAN_MESHES  names in data/meshes without .off (default: lion camel
#                  mannequin-devil man, 7.5k to 17.5k vertices)
#   MESH_CACHE     where the package and meshes are kept (default
#                  OUT_DIR/debian-meshes)
set -euo pipefail

build="${1:-build}"
out="${2:-$(mktemp -d "${TMPDIR:-/tmp}/shellspace-debian-meshes.XXXXXX")}"
cache="${MESH_CACHE:-${out}/debian-meshes}"
read -r -a names <<<"${DEBIAN_MESHES:-lion camel mannequin-devil man}"
mkdir -p "${cache}"

if ! ls "${cache}"/libcgal-demo_*.deb >/dev/null 2>&1; then
  (cd "${cache}" && apt-get download libcgal-demo >/dev/null 2>&1) || {
    echo "$0: apt-get download libcgal-demo failed (a Debian machine with" \
         "its package lists: apt-get update)" >&2
    exit 2
  }
fi
deb="$(ls "${cache}"/libcgal-demo_*.deb | head -n 1)"
if [[ ! -d "${cache}/data/meshes" ]]; then
  rm -rf "${cache}/unpacked"
  dpkg-deb -x "${deb}" "${cache}/unpacked"
  tar -xzf "${cache}/unpacked/usr/share/doc/libcgal-dev/data.tar.gz" \
    -C "${cache}" data/meshes
fi

meshes=()
for name in "${names[@]}"; do
  mesh="${cache}/data/meshes/${name}.off"
  [[ -f "${mesh}" ]] || { echo "$0: ${name}.off is not in ${deb}" >&2; exit 2; }
  meshes+=("${mesh}")
done
echo "meshes from $(basename "${deb}"): ${names[*]}"
echo
CORPUS_MESHES="${meshes[*]}" "$(dirname "${BASH_SOURCE[0]}")/stress_corpus.sh" \
  "${build}" "${out}/runs"
