"""The array-taking functions of `shellspace` and their array arguments.

Shared by test_array_boundary.py (one class of bad input at a time) and
test_array_fuzz.py (random arrays). Each entry calls one function with good
arrays on the shared double square (9 vertices) unless an argument is
replaced; the solving ones with few iterations and allow_unconverged=True,
so that a valid replacement ends quickly and returns.
"""
import ctypes
import mmap
import os

import numpy as np

import shellspace

DATA = os.environ.get("SHELLSPACE_DATA", "../shared/data")
DOUBLE = os.path.join(DATA, "simple", "double_square.ply")
DOUBLE_BENT = os.path.join(DATA, "simple", "double_square_bent.ply")

V, F = shellspace.read_mesh(DOUBLE)
W, _ = shellspace.read_mesh(DOUBLE_BENT)
M = 0.5 * (V + W)
NV = V.shape[0]

QUICK = dict(quiet=True, max_iterations=3, allow_unconverged=True)

# What an argument is: "shape" #V x 3 real, "stack" K x #V x 3 real (an
# array or a list), "faces" #F x 3 integers, "mask" and "at" 1-D integers.
KINDS = {"reference": "shape", "deformed": "shape", "V": "shape",
         "a": "shape", "b": "shape", "start": "shape", "end": "shape",
         "first": "shape", "second": "shape", "variation": "shape",
         "frames": "stack", "path": "stack", "keyframes": "stack",
         "inputs": "stack", "F": "faces", "mask": "mask", "at": "at"}


class Call:
    """One function: its positional arguments (name, good value), the
    keyword arrays, the other keywords."""

    def __init__(self, name, positional, arrays=None, **kwargs):
        self.name = name
        self.function = getattr(shellspace, name)
        self.positional = positional
        self.arrays = arrays or {}
        self.kwargs = kwargs

    def slots(self):
        """The array arguments' names."""
        return [n for n, _ in self.positional if n in KINDS] + list(self.arrays)

    def good(self, slot):
        return dict(self.positional + list(self.arrays.items()))[slot]

    def __call__(self, tmp_dir, **replace):
        args = []
        for name, value in self.positional:
            if name == "file":  # an output file in tmp_dir
                value = os.path.join(str(tmp_dir), value)
            args.append(replace.get(name, value))
        kwargs = dict(self.kwargs)
        for name, value in self.arrays.items():
            kwargs[name] = replace.get(name, value)
        # Other keywords (time_limit, ...) as given.
        positional = {name for name, _ in self.positional}
        kwargs.update({k: v for k, v in replace.items()
                       if k not in positional and k not in self.arrays})
        return self.function(*args, **kwargs)


def calls():
    stack = np.stack([V, M, W])
    varied = V.copy()
    varied[:, 0] += 0.05 * V[:, 1]
    mask = dict(mask=[0])
    return [
        Call("write_mesh", [("file", "w.ply"), ("V", V), ("F", F)]),
        Call("energy", [("reference", V), ("deformed", W), ("F", F)]),
        Call("energy_gradient", [("reference", V), ("deformed", W), ("F", F)]),
        Call("energy_hessian", [("reference", V), ("deformed", W), ("F", F)]),
        Call("compare", [("a", V), ("b", W), ("F", F)]),
        Call("write_gltf", [("file", "w.glb"), ("frames", stack), ("F", F)]),
        Call("write_film_strip", [("file", "w.png"), ("frames", stack),
                                  ("F", F)], width=64),
        Call("geodesic", [("start", V), ("end", W), ("F", F)], mask, steps=2,
             **QUICK),
        Call("log", [("start", V), ("end", W), ("F", F)], mask, steps=2,
             **QUICK),
        Call("shoot", [("first", V), ("second", M), ("F", F)], mask, steps=2,
             **QUICK),
        Call("transport", [("path", stack), ("variation", varied), ("F", F)],
             mask, **QUICK),
        Call("spline", [("keyframes", [V, M, W]), ("at", [0, 1, 2]),
                        ("F", F)], steps=2, **QUICK),
        Call("regress", [("inputs", [V, W]), ("at", [0, 2]), ("F", F)],
             steps=2, **QUICK),
        Call("mean", [("inputs", [V, W]), ("F", F)], **QUICK),
        Call("pca", [("inputs", [V, M, W]), ("F", F)], modes=1, **QUICK),
    ]


CALLS = {c.name: c for c in calls()}


_GUARDS = []  # the guarded buffers stay mapped for the process


def guarded(array):
    """A copy of `array` (C order) whose last byte ends a page that a
    PROT_NONE page follows."""
    page = mmap.PAGESIZE
    nbytes = array.nbytes
    pages = (nbytes + page - 1) // page + 1
    buffer = mmap.mmap(-1, pages * page)
    address = ctypes.addressof(ctypes.c_char.from_buffer(buffer))
    libc = ctypes.CDLL(None, use_errno=True)
    libc.mprotect.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int]
    if libc.mprotect(address + (pages - 1) * page, page, 0) != 0:
        raise OSError(ctypes.get_errno(), "mprotect")
    _GUARDS.append(buffer)
    out = np.frombuffer(buffer, dtype=array.dtype, count=array.size,
                        offset=(pages - 1) * page - nbytes)
    out = out.reshape(array.shape)
    out[...] = array
    return out
