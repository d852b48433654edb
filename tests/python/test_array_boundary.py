"""Every array argument of every array-taking function, one class of bad
input at a time (python/array_arguments.h): wrong shape on each axis, wrong
dtype, non-finite values, indices out of range -- each a clean
shellspace.InputError naming the argument -- and arrays that are valid but
strided, reversed, Fortran-ordered, big-endian, read-only or of another
width, which must give the very results of the plain array.

Cases per class (the parameter lists below; the counts are checked by
test_case_counts so that a shrinking table is noticed).
"""
import os
import re

import numpy as np
import pytest

import shellspace
from boundary_table import CALLS, KINDS, NV, F, V, guarded

# ---- The bad inputs, by kind -------------------------------------------


def as_stack(value):
    return np.asarray(value, dtype=np.float64)


def wrong_shapes(kind, good):
    """(label, value) of a wrong shape on each axis of the kind."""
    if kind == "shape":
        X = np.asarray(good, dtype=np.float64)
        return [("last axis 2", X[:, :2]),
                ("last axis 4", np.hstack([X, X[:, :1]])),
                ("1-D", X.ravel()),
                ("extra axis", X[..., None]),
                ("0-D", np.float64(1.0))]
    if kind == "stack":
        S = as_stack(good)
        items = list(S)
        return [("last axis 2", S[..., :2]),
                ("last axis 4", np.concatenate([S, S[..., :1]], axis=2)),
                ("2-D", S[..., 0]),
                ("4-D", S[..., None]),
                ("one #V x 3 for a stack", S[0]),
                ("a list item #V x 2", items[:1] + [items[1][:, :2]] +
                 items[2:]),
                ("a list item 1-D", [items[0].ravel()] + items[1:])]
    if kind == "faces":
        G = np.asarray(good)
        return [("last axis 2", G[:, :2]),
                ("last axis 4", np.hstack([G, G[:, :1]])),
                ("1-D", G.ravel()),
                ("extra axis", G[..., None])]
    if kind == "mask":
        return [("2-D", np.array([[0]])), ("0-D", np.array(0))]
    return [("2-D", np.array([good]))]  # at


def wrong_dtypes(kind, good):
    if kind in ("shape", "stack"):
        X = as_stack(good)
        return [("complex128", X + 0.5j), ("complex64",
                                            X.astype(np.complex64)),
                ("bool", X > 0), ("object", X.astype(object)),
                ("str", X.astype(str))]
    if kind == "faces":
        G = np.asarray(good)
        return [("float64 integral", G.astype(np.float64)),
                ("float 2.9", G + 0.9), ("bool", G > 0),
                ("complex", G + 0j), ("object", G.astype(object))]
    if kind == "mask":
        return [("float list", [1.0]), ("float array", np.array([1.5])),
                ("bool", [True]), ("complex", np.array([0j]))]
    return [("float", [float(v) for v in good]),
            ("bool", [bool(v) for v in good])]  # at


def non_finite(kind, good):
    out = []
    for label, bad in (("nan", np.nan), ("inf", np.inf), ("-inf", -np.inf)):
        X = as_stack(good).copy()
        X[(1,) * (X.ndim - 1) + (2,)] = bad
        out.append((label, X))
    return out


def out_of_range(kind, good):
    if kind == "faces":
        out = []
        for value in (-1, NV, 2**31, 2**40):
            G = np.asarray(good, dtype=np.int64).copy()
            G[1, 2] = value
            out.append((str(value), G))
        G = np.asarray(good, dtype=np.uint64).copy()
        G[1, 2] = np.uint64(2**64 - 1)
        out.append(("uint64 max", G))
        return out
    if kind == "mask":
        return [(str(v), [v]) for v in (-1, NV, 2**40)]
    return [(str(v), list(good[:-1]) + [v]) for v in (-1, 2**40)]  # at


CLASSES = {"shape": wrong_shapes, "dtype": wrong_dtypes,
           "non-finite": non_finite, "range": out_of_range}
EXPECTED = {"shape": r"must be a ", "dtype": r"must hold (real numbers|"
            r"integers)", "non-finite": r"has the non-finite value",
            "range": r"(outside|out of range)"}
APPLIES = {"shape": ("shape", "stack", "faces", "mask", "at"),
           "dtype": ("shape", "stack", "faces", "mask", "at"),
           "non-finite": ("shape", "stack"),
           "range": ("faces", "mask", "at")}


def bad_cases():
    cases = []
    for call in CALLS.values():
        for slot in call.slots():
            kind = KINDS[slot]
            for cls, make in CLASSES.items():
                if kind not in APPLIES[cls]:
                    continue
                for label, value in make(kind, call.good(slot)):
                    # A 1 x #V x 3 array is a one-frame path for compare.
                    if call.name == "compare" and label == "extra axis":
                        continue
                    cases.append(pytest.param(
                        call.name, slot, cls, value,
                        id="%s-%s-%s-%s" % (cls, call.name, slot, label)))
    return cases


BAD = bad_cases()


@pytest.mark.parametrize("name,slot,cls,value", BAD)
def test_bad_array_is_an_input_error_naming_it(tmp_path, name, slot, cls,
                                               value):
    with pytest.raises(shellspace.InputError) as error:
        CALLS[name](tmp_path, **{slot: value})
    message = str(error.value)
    # The argument is named (a list item as name[k]; a mask and a face
    # by their own words).
    assert re.match(r"%s(\[\d+\])?[ :]" % re.escape(slot), message), message
    assert re.search(EXPECTED[cls], message), message
    assert "\n" not in message
    # Nothing was written.
    assert not os.listdir(tmp_path)


# ---- Valid arrays in other layouts give the same results ---------------


def layouts(kind, good):
    """(label, value) of the same values in another memory layout or
    width."""
    if kind in ("shape", "stack"):
        X = as_stack(good)
        reversed_copy = X[::-1].copy()
        big = np.zeros(tuple(2 * n for n in X.shape))
        big[tuple(slice(None, None, 2) for _ in X.shape)] = X
        read_only = X.copy()
        read_only.flags.writeable = False
        out = [("fortran", np.asfortranarray(X)),
               ("reversed view", reversed_copy[::-1]),
               ("strided", big[tuple(slice(None, None, 2) for _ in X.shape)]),
               ("big-endian", X.astype(">f8")),
               ("read-only", read_only),
               ("long double", X.astype(np.longdouble))]
        if kind == "stack":
            out.append(("list of strided", [np.asfortranarray(s) for s in X]))
            out.append(("tuple of nested lists", tuple(s.tolist() for s in X)))
        else:
            out.append(("nested list", X.tolist()))
        return out
    G = np.asarray(good)
    if kind == "faces":
        big = np.zeros((2 * G.shape[0], 6), dtype=np.int64)
        big[::2, ::2] = G
        return [("fortran", np.asfortranarray(G)), ("strided", big[::2, ::2]),
                ("int32", G.astype(np.int32)), ("uint16", G.astype(np.uint16)),
                ("int8", G.astype(np.int8)), ("uint64", G.astype(np.uint64)),
                ("big-endian", G.astype(">i4")), ("nested list", G.tolist())]
    return [("uint8", G.astype(np.uint8)), ("strided",
                                           np.repeat(G, 2)[::2]),
            ("tuple", tuple(int(v) for v in G))]


def layout_cases():
    cases = []
    for call in CALLS.values():
        for slot in call.slots():
            for label, value in layouts(KINDS[slot], call.good(slot)):
                cases.append(pytest.param(call.name, slot, value,
                                          id="%s-%s-%s" % (call.name, slot,
                                                           label)))
    return cases


LAYOUTS = layout_cases()


def same(a, b):
    """a and b equal to the bit, apart from wall-clock entries."""
    if hasattr(a, "to_dict"):  # a result: the pair (value, summary)
        assert type(a) is type(b)
        a, b = tuple(a), tuple(b)
    if isinstance(a, dict):
        assert set(a) == set(b)
        for k in a:
            if "seconds" not in k:
                same(a[k], b[k])
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            same(x, y)
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and np.array_equal(a, b)
    else:
        assert a == b


def files(folder):
    return {name: open(os.path.join(folder, name), "rb").read()
            for name in sorted(os.listdir(folder))}


@pytest.mark.parametrize("name,slot,value", LAYOUTS)
def test_other_layouts_give_the_same_result(tmp_path, name, slot, value):
    os.mkdir(tmp_path / "plain")
    os.mkdir(tmp_path / "other")
    expected = CALLS[name](tmp_path / "plain")
    got = CALLS[name](tmp_path / "other", **{slot: value})
    same(got, expected)
    assert files(tmp_path / "other") == files(tmp_path / "plain")


# ---- Named cases of the report -----------------------------------------


def test_a_frame_stack_with_two_coordinates_is_refused_not_read(tmp_path):
    # The read past the array: (K, #V, 2) where (K, #V, 3) is expected, at
    # the end of a page-aligned buffer (the guard page SIGSEGVed before).
    frames = guarded(np.stack([V, V, V])[..., :2].copy())
    for name in ("mean", "write_gltf", "write_film_strip", "transport"):
        with pytest.raises(shellspace.InputError, match=r"must be a K x #V "
                           r"x 3 array, got shape \(3, 9, 2\)"):
            slot = {"mean": "inputs", "transport": "path"}.get(name, "frames")
            CALLS[name](tmp_path, **{slot: frames})


def test_float_faces_are_refused_not_truncated(tmp_path):
    with pytest.raises(shellspace.InputError,
                       match=r"F must hold integers, got dtype float64 "
                       r"\(indices are not rounded\)"):
        shellspace.energy(V, V, F + 0.9)


def test_a_float_mask_is_an_input_error():
    for mask in ([1.0], np.array([2.0]), (0.5,)):
        with pytest.raises(shellspace.InputError,
                           match=r"^mask must hold integers"):
            shellspace.shoot(V, V, F, steps=2, mask=mask, quiet=True)
    # An empty list (numpy: float64) holds no index: no vertex held.
    _, summary = shellspace.shoot(V, V, F, steps=2, mask=[], quiet=True)
    assert summary["frames"] == 3


def test_complex_positions_are_refused_not_truncated():
    with pytest.raises(shellspace.InputError,
                       match=r"^reference must hold real numbers, got dtype "
                       r"complex128$"):
        shellspace.energy(V + 1e-3j, V, F)


def test_case_counts():
    # The tables' sizes (the report's counts per class): a case that
    # disappears from a table is a change to review.
    counts = {}
    for p in BAD:
        counts[p.values[2]] = counts.get(p.values[2], 0) + 1
    counts["layout"] = len(LAYOUTS)
    print("cases per class:", counts)
    assert counts == {"shape": 196, "dtype": 210, "non-finite": 69,
                      "range": 91, "layout": 306}, counts
