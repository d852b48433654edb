"""Builds the extension module `shellspace` with CMake for pip.

`pip install .` (or `pip install --no-build-isolation .` offline, with
Debian's python3-setuptools and pybind11-dev) configures the project in a
temporary build folder with the library, the CLI's memory bounds and the
module only (no tests, benchmarks or examples), builds the target
shellspace_python with the running interpreter, and installs:

    shellspace.cpython-*.so            the module
    shellspace/collections/*.py        shellspace.collections
    shellspace/__init__.pyi, py.typed  the type stubs (PEP 561)

Environment: SHELLSPACE_CMAKE_ARGS (extra cmake arguments, split at
spaces), SHELLSPACE_CMAKE_BUILD_DIR (an already configured build folder to
build the module in instead, e.g. build/: the module is then the one of
that build), CMAKE_BUILD_PARALLEL_LEVEL (parallel jobs, default 2).
"""
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.environ.get("SHELLSPACE_CMAKE_BUILD_DIR")
        if build:
            build = os.path.abspath(build)
        else:
            build = os.path.abspath(os.path.join(self.build_temp, "cmake"))
            os.makedirs(build, exist_ok=True)
            configure = [
                "cmake", "-S", HERE, "-B", build,
                "-DCMAKE_BUILD_TYPE=Release",
                "-DSHELLSPACE_BUILD_TESTS=OFF",
                "-DSHELLSPACE_BUILD_BENCHMARKS=OFF",
                "-DSHELLSPACE_BUILD_EXAMPLES=OFF",
                "-DSHELLSPACE_BUILD_PYTHON=ON",
                "-DPython_EXECUTABLE=" + sys.executable,
            ] + os.environ.get("SHELLSPACE_CMAKE_ARGS", "").split()
            subprocess.run(configure, check=True)
        env = dict(os.environ)
        env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
        subprocess.run(["cmake", "--build", build, "--target",
                        "shellspace_python"], check=True, env=env)
        module = os.path.join(build, "python", os.path.basename(
            self.get_ext_filename(ext.name)))
        if not os.path.isfile(module):
            raise RuntimeError(
                "the CMake build made no " + module + " (is its Python " +
                sys.executable + "?)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(module, target)


setup(
    ext_modules=[CMakeExtension("shellspace")],
    cmdclass={"build_ext": CMakeBuild},
    packages=["shellspace", "shellspace.collections"],
    package_dir={"shellspace": "python/shellspace"},
    package_data={"shellspace": ["__init__.pyi", "py.typed"]},
    zip_safe=False,
    # Not build/, the CMake build folder of docs/install.md.
    options={"build": {"build_base": "build-pip"}},
)
