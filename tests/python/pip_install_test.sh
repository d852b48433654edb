#!/usr/bin/env bash
# Usage: tests/python/pip_install_test.sh SOURCE_DIR BUILD_DIR PYTHON
#
# `pip install --no-build-isolation .` of a copy of SOURCE_DIR into a fresh
# venv (--system-site-packages: NumPy from the system), offline, as
# docs/install.md gives it; the module is built in BUILD_DIR
# (SHELLSPACE_CMAKE_BUILD_DIR: the configured build of this test run, so
# the install takes seconds, not a build of the library). Then, from a
# folder outside both trees: `import shellspace` and
# `shellspace.collections` come from the venv, the type stubs
# (__init__.pyi, py.typed) are installed and are the stub of this module
# (python/make_stubs.py --check), a mesh round trip and an energy work,
# bad input raises InputError, and `pip uninstall` removes it all.
set -euo pipefail
src="${1:?usage: $0 SOURCE_DIR BUILD_DIR PYTHON}"
build="${2:?}"
python="${3:?}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# pip builds in the source folder (egg-info, build-pip/): a copy keeps the
# checkout clean.
mkdir "$tmp/src"
tar -C "$src" --exclude=./build --exclude='./build-*' --exclude=./.git \
  --exclude='*.egg-info' -cf - . | tar -C "$tmp/src" -xf -
"$python" -m venv --system-site-packages "$tmp/venv"
venv_python="$tmp/venv/bin/python"
env -u PYTHONPATH -u SHELLSPACE_DATA SHELLSPACE_CMAKE_BUILD_DIR="$build" PIP_NO_INDEX=1 \
  "$venv_python" -m pip install --quiet --no-build-isolation --no-deps \
  --disable-pip-version-check "$tmp/src"
cd "$tmp"
env -u PYTHONPATH "$venv_python" - "$tmp/venv" "$src" <<'PY'
import os, subprocess, sys
import numpy as np
import shellspace, shellspace.collections
venv, src = sys.argv[1], sys.argv[2]
site = os.path.dirname(shellspace.__file__)
assert shellspace.__file__.startswith(venv), shellspace.__file__
assert shellspace.collections.__file__ == os.path.join(site, "shellspace", "collections", "__init__.py")
for name in ("__init__.pyi", "py.typed"):
    assert os.path.isfile(os.path.join(site, "shellspace", name)), name
subprocess.run([sys.executable, os.path.join(src, "python", "make_stubs.py"),
                "--check", os.path.join(site, "shellspace", "__init__.pyi")],
               check=True)
# A square of two triangles, written, read back, flat and folded.
V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
F = np.array([[0, 1, 2], [0, 2, 3]])
path = os.path.join(os.getcwd(), "square.ply")
shellspace.write_mesh(path, V, F)
V2, F2 = shellspace.read_mesh(path)
assert np.array_equal(V2, V) and np.array_equal(F2, F)
W = V.copy(); W[3, 2] = 0.5
assert shellspace.energy(V, V, F)["total"] == 0
assert shellspace.energy(V, W, F)["total"] > 0
try:
    shellspace.energy(V, W, F[:, :2])
    raise SystemExit("no InputError for #F x 2 faces")
except shellspace.InputError:
    pass
print("installed", shellspace.__file__)
PY
env -u PYTHONPATH "$venv_python" -m pip uninstall --quiet --yes shellspace
if env -u PYTHONPATH "$venv_python" -c "import shellspace, sys
sys.exit(0 if shellspace.__file__.startswith('$tmp/venv') else 1)" 2>/dev/null; then
  echo "shellspace still imported from the venv after pip uninstall"
  exit 1
fi
left="$(find "$tmp/venv" -name 'shellspace*' | head -5)"
if [ -n "$left" ]; then
  echo "left after pip uninstall: $left"
  exit 1
fi
echo "pip install: ok"
