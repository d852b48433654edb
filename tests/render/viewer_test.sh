#!/usr/bin/env bash
# Usage: tests/render/viewer_test.sh SHELLSPACE_CLI
#
# The viewer page (render/html_viewer.h) in headless Chromium:
# - `geodesic --html` of the finger example: the page draws (data-status
#   "ready"), shows the summary's E_K, and logs nothing to the console
#   (Chromium's performance notes about reading pixels back aside);
# - screenshots at the first and the last frame both show the shape and
#   differ where it moved;
# - `view` of a path of 20,000 vertices x 9 frames draws in under 5 s.
# Exits 77 (CTest: skipped) only if chromium is not installed.
set -euo pipefail
cli="${1:?usage: $0 SHELLSPACE_CLI}"
here="$(cd "$(dirname "$0")" && pwd)"
if ! command -v chromium >/dev/null; then
  echo "viewer test skipped: chromium is not installed"
  exit 77
fi
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
browser() {  # chromium headless with a fresh profile; its log in $tmp/log
  timeout 120 chromium --headless --no-sandbox --disable-gpu --disable-quic \
    --no-first-run --disable-background-networking --disable-component-update \
    --disable-sync --enable-unsafe-swiftshader --user-data-dir="$(mktemp -d -p "$tmp")" \
    --enable-logging=stderr --v=0 --window-size=900,600 "$@" 2>"$tmp/log"
}
console_errors() {  # the page's console lines but Chromium's performance notes
  grep ':CONSOLE' "$tmp/log" | grep -v 'GL Driver Message (OpenGL, Performance' || true
}

cd "$tmp"
"$cli" example finger --output finger --quiet
"$cli" geodesic --start finger/finger0.ply --end finger/finger1.ply \
  --mask finger/finger_mask.txt --steps 4 --output morph --html morph.html --quiet
browser --dump-dom "file://$tmp/morph.html" > dom.html
status=$(grep -o 'data-status="[a-z]*"' dom.html | head -1)
[ "$status" = 'data-status="ready"' ] || { echo "viewer: page status $status"; grep -o '<div id="error">[^<]*' dom.html; exit 1; }
errors=$(console_errors)
[ -z "$errors" ] || { echo "viewer: console messages:"; echo "$errors"; exit 1; }
energy=$(python3 -c 'import json; print(json.load(open("morph/summary.json"))["path_energy"])')
grep -q "E_K (path energy)" dom.html || { echo "viewer: no E_K on the page"; exit 1; }
grep -q '<td>converged</td><td>true</td>' dom.html || { echo "viewer: converged not shown as true"; exit 1; }
echo "viewer: geodesic page ready (E_K $energy in its summary), no console message"

browser --screenshot="$tmp/first.png" "file://$tmp/morph.html#frame=0" >/dev/null
browser --screenshot="$tmp/last.png" "file://$tmp/morph.html#frame=last" >/dev/null
read -r _ differ < <(python3 "$here/png_pixels.py" first.png last.png | grep differ)
read -r _ first last < <(python3 "$here/png_pixels.py" first.png last.png | grep coloured)
echo "viewer: first frame covers $first of the picture, last $last; $differ of the pixels differ"
python3 -c "import sys; f, l, d = map(float, sys.argv[1:]); sys.exit(0 if f > 0.03 and l > 0.03 and d > 0.02 else 1)" \
  "$first" "$last" "$differ" || { echo "viewer: the frames are blank or the same"; exit 1; }

# 20,000 vertices (a 141 x 141 grid) x 9 frames, a travelling wave.
python3 - <<'PY'
import math
n = 141
faces = []
for r in range(n - 1):
    for c in range(n - 1):
        v = r * n + c
        faces += [(v, v + 1, v + n + 1), (v, v + n + 1, v + n)]
for k in range(9):
    with open(f"wave_{k}.ply", "w") as out:
        out.write(f"ply\nformat ascii 1.0\nelement vertex {n * n}\nproperty float x\n"
                  f"property float y\nproperty float z\nelement face {len(faces)}\n"
                  "property list uchar int vertex_indices\nend_header\n")
        for r in range(n):
            for c in range(n):
                x, y = c / (n - 1), r / (n - 1)
                out.write(f"{x} {y} {0.1 * k / 8 * math.sin(6 * x + k)}\n")
        for f in faces:
            out.write(f"3 {f[0]} {f[1]} {f[2]}\n")
PY
"$cli" view --input "$(ls wave_*.ply | paste -sd,)" --output wave.html --quiet
start=$(date +%s%N)
browser --dump-dom "file://$tmp/wave.html" > wave_dom.html
wall=$(( ($(date +%s%N) - start) / 1000000 ))
grep -q 'data-status="ready"' wave_dom.html || { echo "viewer: the 20k page did not draw"; exit 1; }
load=$(grep -o 'data-load-ms="[0-9]*"' wave_dom.html | grep -o '[0-9]*')
echo "viewer: 20,000 vertices x 9 frames ($(du -k wave.html | cut -f1) KB) drawn $load ms after its script started; chromium ran $wall ms"
[ "$load" -lt 5000 ] || { echo "viewer: the 20k page took $load ms (limit 5000)"; exit 1; }
