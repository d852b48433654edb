"""A fuzz of the array boundary: random shapes, dtypes, strides, memory
layouts and values given to every array argument of every array-taking
function (boundary_table.py). Each call must end in success (a result),
shellspace.InputError or TypeError: never another exception, a crash, or a
read outside an array. Some arrays end flush against a PROT_NONE page, so
that a read past their end is a SIGSEGV even without a sanitizer.

In CI (ctest python_array_fuzz): seed SHELLSPACE_FUZZ_SEED (34), at most
SHELLSPACE_FUZZ_CASES calls (6000, about 6 s) and SHELLSPACE_FUZZ_SECONDS
of them (20; 0: no bound).

Under AddressSanitizer: the module alone instrumented, in its own folder
build/python-asan (python/CMakeLists.txt, SHELLSPACE_PYTHON_ASAN; the
library rooms are the normal build's). The interpreter is not instrumented,
so the ASan runtime is preloaded and leak detection is off (Python's own
allocations). From the checkout, after the normal build:

  cmake -S . -B build -DSHELLSPACE_PYTHON_ASAN=ON
  cmake --build build -j2 --target shellspace_python_asan
  ASAN_OPTIONS=detect_leaks=0 \\
    LD_PRELOAD="$(gcc -print-file-name=libasan.so) $(gcc -print-file-name=libstdc++.so)" \\
    PYTHONPATH=build/python-asan SHELLSPACE_DATA=../shared/data \\
    SHELLSPACE_FUZZ_CASES=20000 SHELLSPACE_FUZZ_SECONDS=0 \\
    python3 -m pytest -q -s -p no:cacheprovider tests/python/test_array_fuzz.py
"""
import os
import time
import warnings

import numpy as np

import shellspace
from boundary_table import CALLS, KINDS, NV, guarded

SEED = int(os.environ.get("SHELLSPACE_FUZZ_SEED", "34"))
CASES = int(os.environ.get("SHELLSPACE_FUZZ_CASES", "6000"))
SECONDS = float(os.environ.get("SHELLSPACE_FUZZ_SECONDS", "20"))

DTYPES = ["f8", "f4", "f2", "g", ">f8", "i8", "i4", "u1", "u8", ">i4", "?",
          "c16", "O", "U4"]

def random_shape(rng, good_shape):
    shape = list(good_shape)
    r = rng.random()
    if r < 0.45:
        return shape
    if r < 0.85 and shape:
        axis = int(rng.integers(len(shape)))
        shape[axis] = int(rng.choice([0, 1, 2, 4, shape[axis] - 1,
                                      shape[axis] + 1]))
        return [max(0, n) for n in shape]
    return [int(n) for n in rng.integers(0, 6, size=int(rng.integers(0, 5)))]


def random_values(rng, kind, good, shape):
    if kind in ("faces", "mask", "at"):
        if list(good.shape) == shape and rng.random() < 0.5:
            values = good.astype(np.int64).copy()
            if values.size and rng.random() < 0.5:
                values.flat[int(rng.integers(values.size))] = int(
                    rng.choice([-1, NV, 2**31, -2**40]))
            return values
        return rng.integers(-2, NV + 3, size=shape)
    if list(good.shape) == shape and rng.random() < 0.6:
        values = good + 1e-3 * rng.standard_normal(shape)
    else:
        values = rng.standard_normal(shape) * 10.0 ** int(rng.integers(-3, 4))
    if values.size and rng.random() < 0.15:
        values.flat[int(rng.integers(values.size))] = rng.choice(
            [np.nan, np.inf, -np.inf, 1e308])
    return values


def with_dtype(rng, values, kind):
    natural = "i8" if kind in ("faces", "mask", "at") else "f8"
    dtype = natural if rng.random() < 0.5 else str(rng.choice(DTYPES))
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if dtype == "O":
            return values.astype(object)
        if dtype == "U4":
            return values.astype("U4")
        if dtype == "c16":
            return values + 0.5j
        return values.astype(dtype)


def with_layout(rng, array, kind):
    r = rng.random()
    if r < 0.3 or array.dtype.kind in "OU":
        return array
    if r < 0.45:
        return np.asfortranarray(array)
    if r < 0.6 and array.ndim:
        big = np.zeros(tuple(2 * n + 1 for n in array.shape),
                       dtype=array.dtype)
        view = big[tuple(slice(1, None, 2) for _ in array.shape)]
        view[...] = array
        return view
    if r < 0.7 and array.ndim:
        return array[::-1].copy()[::-1]
    if r < 0.85:
        return guarded(np.ascontiguousarray(array))
    if kind == "stack" and array.ndim:
        return [guarded(np.ascontiguousarray(a)) for a in array]
    return array.tolist()


def random_argument(rng, kind, good):
    good = np.asarray(good)
    shape = random_shape(rng, good.shape)
    values = np.asarray(random_values(rng, kind, good, shape))
    return with_layout(rng, with_dtype(rng, values, kind), kind)


def test_fuzz_the_array_boundary(tmp_path):
    rng = np.random.default_rng(SEED)
    names = sorted(CALLS)
    tally = {}
    failures = []
    start = time.monotonic()
    for case in range(CASES):
        if SECONDS and time.monotonic() - start > SECONDS:
            break
        call = CALLS[names[int(rng.integers(len(names)))]]
        slots = call.slots()
        chosen = [slots[int(rng.integers(len(slots)))]]
        if rng.random() < 0.25:
            chosen.append(slots[int(rng.integers(len(slots)))])
        replace = {slot: random_argument(rng, KINDS[slot], call.good(slot))
                   for slot in chosen}
        try:
            call(tmp_path, **replace)
            outcome = "result"
        except shellspace.InputError:
            outcome = "InputError"
        except TypeError:
            outcome = "TypeError"
        except Exception as error:  # anything else is a finding
            outcome = type(error).__name__
            failures.append("case %d: %s(%s): %s: %s" % (
                case, call.name, ", ".join(chosen), type(error).__name__,
                error))
        key = (call.name, outcome)
        tally[key] = tally.get(key, 0) + 1
    total = sum(tally.values())
    print("\nfuzz seed %d: %d calls in %.1f s" % (SEED, total,
                                                  time.monotonic() - start))
    for name in names:
        print("  %-17s %s" % (name, ", ".join(
            "%s %d" % (o, n) for (c, o), n in sorted(tally.items())
            if c == name)))
    assert not failures, "\n".join(failures[:20])
    # Every function was reached, and both outcomes occurred.
    assert {c for c, _ in tally} == set(names)
    assert {o for _, o in tally} >= {"result", "InputError"}
