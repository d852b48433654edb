#!/usr/bin/env bash
# Usage: tests/io/gltf_validate_test.sh SHELLSPACE_CLI DATA_DIR NODE_MODULES
#
# Writes .glb files the ways the CLI does (--gltf of geodesic, shoot,
# transport, spline, regress and demo; export of a frame directory, of a list
# with STEP keys, of a single mesh)
# and validates each with the Khronos glTF validator (tests/io/
# validate_gltf.js): no errors. Exits 77 (CTest: skipped) only if node is
# not installed.
set -euo pipefail
cli="${1:?usage: $0 CLI DATA_DIR NODE_MODULES}"
data="${2:?}"
export NODE_PATH="${3:?}"
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v node >/dev/null; then
  echo "gltf validation skipped: node (Node.js) is not installed"
  exit 77
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
a="$data/simple/double_square.ply"
b="$data/simple/double_square_bent.ply"
"$cli" geodesic --start "$a" --end "$b" --steps 4 --output "$tmp/geo" \
  --gltf "$tmp/geodesic.glb" --quiet
g="$tmp/geo"
# Every verb that writes frames writes the same frames as a .glb.
"$cli" shoot --first "$g/shape_000.ply" --second "$g/shape_001.ply" --steps 3 \
  --output "$tmp/shoot" --gltf "$tmp/shoot.glb" --quiet --allow_unconverged
"$cli" transport --path "$g" --variation "$g/shape_001.ply" \
  --output "$tmp/transport" --gltf "$tmp/transport.glb" --quiet --allow_unconverged
"$cli" spline --keyframes "$g/shape_000.ply,$g/shape_002.ply,$g/shape_004.ply" \
  --at 0,2,4 --steps 4 --output "$tmp/spline" --gltf "$tmp/spline.glb" --quiet --allow_unconverged
"$cli" regress --inputs "$g/shape_000.ply,$g/shape_004.ply" --at 0,4 \
  --steps 4 --output "$tmp/regress" --gltf "$tmp/regress.glb" --quiet --allow_unconverged
"$cli" demo --steps 2 --extrapolate 1 --output "$tmp/demo" \
  --gltf "$tmp/demo.glb" --quiet >/dev/null
"$cli" export --input "$tmp/geo" --output "$tmp/export_dir.glb" --quiet
"$cli" export --input "$tmp/geo/shape_000.ply,$tmp/geo/shape_004.ply" \
  --output "$tmp/export_list.glb" \
  --interpolation step --fps 2 --quiet
"$cli" export --input "$a" --output "$tmp/single.glb" --quiet
for verb in geodesic shoot transport spline regress demo; do
  [ -s "$tmp/$verb.glb" ] || { echo "$verb wrote no $tmp/$verb.glb"; exit 1; }
done
node "$here/validate_gltf.js" "$tmp"/{geodesic,shoot,transport,spline,regress,demo}.glb \
  "$tmp/export_dir.glb" "$tmp/export_list.glb" "$tmp/single.glb"
