"""The options classes of the workflow functions (python/module_options.h):
each holds exactly its function's keyword arguments with the function's
defaults, checks names and kinds, and passes as **options to the same
result as the keywords.
"""
import pickle
import re

import numpy as np
import pytest

import shellspace
from procedural import plate

CLASSES = {"geodesic": "GeodesicOptions", "log": "LogOptions",
           "shoot": "ShootOptions", "transport": "TransportOptions",
           "spline": "SplineOptions", "regress": "RegressOptions",
           "mean": "MeanOptions", "pca": "PcaOptions"}


def split_top_level(inner):
    parts, depth, current, quote = [], 0, "", None
    for c in inner:
        if quote:
            quote = None if c == quote else quote
        elif c in "'\"":
            quote = c
        elif c in "[(":
            depth += 1
        elif c in "])":
            depth -= 1
        if c == "," and depth == 0 and not quote:
            parts.append(current.strip())
            current = ""
        else:
            current += c
    return parts + [current.strip()] if current.strip() else parts


def signature_defaults(function_name):
    """{keyword: default as pybind11 prints it} of the function's own
    signature line (its docstring's first line): an expectation independent
    of the options class, which collects them from the py::arg list."""
    first = getattr(shellspace, function_name).__doc__.split("\n", 1)[0]
    m = re.match(r"^%s\((.*)\) -> " % function_name, first)
    assert m, first
    out = {}
    for part in split_top_level(m.group(1)):
        m = re.match(r"^(\w+): [^=]+? = (.*)$", part)
        if m:
            out[m.group(1)] = m.group(2)
    return out


def defaults_mismatch(options, expected):
    """The keywords whose names, order or defaults differ (empty: none)."""
    got = {name: repr(value) for name, value in options.to_dict().items()}
    if list(got) != list(expected):
        return ["order: %s != %s" % (list(got), list(expected))]
    return [k for k in got if got[k] != expected[k]]


@pytest.mark.parametrize("function", sorted(CLASSES))
def test_the_options_are_the_function_keywords_with_its_defaults(function):
    cls = getattr(shellspace, CLASSES[function])
    assert cls.function == function
    expected = signature_defaults(function)
    assert len(expected) >= 11  # the material and solver keywords at least
    assert defaults_mismatch(cls(), expected) == []
    # Every option is documented on a line of its own.
    for name in expected:
        assert re.search(r"^    %s: " % name, cls.__doc__, re.M), name


def test_a_changed_default_is_caught():
    # The twin of the test above through the same helper.
    expected = signature_defaults("geodesic")
    changed = shellspace.GeodesicOptions(steps=9)
    assert defaults_mismatch(changed, expected) == ["steps"]
    expected.pop("mask")
    assert defaults_mismatch(shellspace.GeodesicOptions(), expected) != []


def test_options_pass_as_keywords_to_the_same_digits():
    V, F = plate()
    end = V.copy()
    end[:, 2] = 0.5 * (V[:, 0] - 0.5) ** 2
    options = shellspace.GeodesicOptions(steps=3, relative_eta=1e-3,
                                         quiet=True)
    options.tolerance = 1e-10
    by_options = shellspace.geodesic(V, end, F, **options)
    by_keywords = shellspace.geodesic(V, end, F, steps=3, relative_eta=1e-3,
                                      quiet=True, tolerance=1e-10)
    assert np.array_equal(by_options.path, by_keywords.path)
    assert by_options.path_energy == by_keywords.path_energy
    assert len(by_options.path) == 4
    # The options are not the defaults: the default solve differs.
    default = shellspace.geodesic(V, end, F, quiet=True)
    assert len(default.path) == 9


def test_names_and_kinds_are_checked():
    options = shellspace.GeodesicOptions()
    with pytest.raises(AttributeError, match="no option 'stepz'"):
        options.stepz = 4
    with pytest.raises(TypeError, match="unexpected keyword argument 'stepz'"):
        shellspace.GeodesicOptions(stepz=4)
    with pytest.raises(TypeError, match="keyword arguments only"):
        shellspace.GeodesicOptions(4)
    for name, bad in [("steps", 2.5), ("steps", True), ("steps", "8"),
                      ("tolerance", "1e-8"), ("tolerance", False),
                      ("quiet", 1), ("multires", 2), ("mask", 3.5),
                      ("mask", 7), ("mask", True), ("mask", b"m.txt")]:
        with pytest.raises(TypeError, match="GeodesicOptions.%s takes" % name):
            setattr(options, name, bad)
    with pytest.raises(AttributeError, match="cannot be deleted"):
        del options.steps
    assert options == shellspace.GeodesicOptions()  # nothing was set
    # Integers and reals of NumPy are integers and reals; None-default
    # options take what the function takes.
    options.steps = np.int64(3)
    options.tolerance = np.float32(1e-6)
    options.tolerance = 1  # an int is a real number
    options.mask = "m.txt"
    options.mask = np.array([0, 1])
    options.mask = [0, 1, 2]
    options.time_limit = 5
    assert options.steps == 3 and options.mask == [0, 1, 2]


def test_repr_equality_and_pickling():
    options = shellspace.SplineOptions(steps=12, method="linear",
                                       periodic=True)
    assert options["steps"] == 12
    assert list(options) == list(options.keys())
    assert len(options) == len(options.keys())
    with pytest.raises(KeyError):
        options["stepz"]
    again = eval(repr(options), {"SplineOptions": shellspace.SplineOptions})
    assert again == options and again is not options
    assert pickle.loads(pickle.dumps(options)) == options
    assert options != shellspace.SplineOptions()
    assert options != shellspace.RegressOptions()
    assert options.to_dict()["method"] == "linear"
