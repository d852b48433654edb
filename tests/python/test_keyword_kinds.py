"""The keywords' kinds at the Python boundary, in every function and
options class: a bool is not a count or a number (python/strict_numbers.h,
python/module_options.h), eta and relative_eta are one or the other, the
arrays of a solving function's result are read-only, a film strip too
large is refused up front, branching_simulate raises what the CLI exits 4
for, and docstrings say what the functions do.
"""
import pickle
import re

import numpy as np
import pytest

import shellspace
from procedural import plate

FUNCTIONS = sorted(
    name for name in dir(shellspace)
    if not name.startswith("_") and callable(getattr(shellspace, name))
    and not isinstance(getattr(shellspace, name), type))
OPTIONS = sorted(name for name in dir(shellspace) if name.endswith("Options"))


def split_top_level(inner):
    """The parameters of a signature line: commas outside brackets and
    quotes."""
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


def parameters(name):
    """[(name, annotation, has_default)] of the signature line."""
    first = getattr(shellspace, name).__doc__.split("\n", 1)[0]
    m = re.match(r"^%s\((.*)\) -> " % name, first)
    assert m, first
    out = []
    for part in split_top_level(m.group(1)):
        m = re.match(r"^(\w+): ([^=]+?)(?: = .*)?$", part)
        assert m, part
        out.append((m.group(1), m.group(2), " = " in part))
    return out


NUMBER_PARAMETERS = [
    (f, p) for f in FUNCTIONS for p, kind, _ in parameters(f)
    if kind in ("int", "float", "Optional[float]")]


def test_every_number_parameter_is_listed():
    # The table below is not empty by accident: steps, tolerance, eta, ...
    names = {p for _, p in NUMBER_PARAMETERS}
    assert {"steps", "tolerance", "max_iterations", "threads", "eta",
            "relative_eta", "mu", "width", "nx", "shift"} <= names
    assert len(NUMBER_PARAMETERS) >= 80


@pytest.mark.parametrize("function,name", NUMBER_PARAMETERS)
@pytest.mark.parametrize("value", [True, False, np.bool_(True)])
def test_a_bool_is_refused_where_a_number_is_meant(function, name, value):
    # Refused while the arguments are read: the other arguments are
    # placeholders of their kind (read before this one), nothing runs.
    required = {p: "x" if kind == "str" else None
                for p, kind, has in parameters(function)
                if not has and p != name}
    with pytest.raises(TypeError, match="got the bool"):
        getattr(shellspace, function)(**required, **{name: value})


def test_steps_true_was_one_step_and_is_refused():
    V, F = plate()
    end = V.copy()
    end[:, 2] = 0.3 * V[:, 0]
    with pytest.raises(TypeError, match=r"expected an int, got the bool True"):
        shellspace.geodesic(V, end, F, steps=True, quiet=True)
    with pytest.raises(TypeError, match="got the bool"):
        shellspace.write_film_strip("x.png", [V], F, width=True)
    # The twin: an int (and a NumPy integer, a real for a float) passes.
    path, _ = shellspace.geodesic(V, end, F, steps=np.int64(1), quiet=True,
                                  mu=1, lambda_=np.float32(1))
    assert path.shape == (2, 25, 3)


OPTION_NUMBERS = [
    (cls, name) for cls in OPTIONS
    for name, value in getattr(shellspace, cls)().to_dict().items()
    if (type(value) in (int, float)) or name in ("eta", "time_limit")]


@pytest.mark.parametrize("cls,name", OPTION_NUMBERS)
def test_options_refuse_a_bool_for_a_number(cls, name):
    options = getattr(shellspace, cls)()
    for value in (True, np.bool_(False)):
        with pytest.raises(TypeError, match=r"%s\.%s takes" % (cls, name)):
            setattr(options, name, value)
        with pytest.raises(TypeError, match=r"%s\.%s takes" % (cls, name)):
            getattr(shellspace, cls)(**{name: value})
    assert options == getattr(shellspace, cls)()


def test_none_options_take_their_kind_only():
    options = shellspace.GeodesicOptions()
    for name, bad in [("eta", "1e-3"), ("eta", True), ("time_limit", "5"),
                      ("time_limit", [5]), ("output", 3), ("png", True),
                      ("gltf", b"x.glb")]:
        with pytest.raises(TypeError, match="GeodesicOptions.%s takes None"
                                            % name):
            setattr(options, name, bad)
    # The twins: None, a real number, a str.
    options.eta = 1e-3
    options.eta = None
    options.time_limit = np.float64(2)
    options.output = "dir"
    options.png = None
    options.mask = "mask.txt"
    assert options.output == "dir" and options.time_limit == 2


def test_eta_and_relative_eta_are_one_or_the_other():
    V, F = plate()
    for call in (lambda **k: shellspace.energy(V, V, F, **k),
                 lambda **k: shellspace.geodesic(V, V, F, steps=1,
                                                 quiet=True, **k)):
        with pytest.raises(shellspace.InputError,
                           match="eta and relative_eta: give one of them"):
            call(eta=1e-3, relative_eta=2e-3)
        # Even a relative_eta equal to the default is given.
        with pytest.raises(shellspace.InputError, match="give one of them"):
            call(eta=1e-3, relative_eta=shellspace.DEFAULT_RELATIVE_ETA)
        # Either alone passes.
        call(eta=1e-3)
        call(relative_eta=2e-3)
    summary = shellspace.energy(V, V, F, eta=1e-3)
    assert summary["eta"] == 1e-3
    # An options object with eta keeps relative_eta its default, also after
    # pickling and through to_dict(); one with both is refused by the call.
    options = shellspace.GeodesicOptions(eta=1e-3, steps=1, quiet=True)
    for copy in (options, pickle.loads(pickle.dumps(options)),
                 shellspace.GeodesicOptions(**options.to_dict())):
        shellspace.geodesic(V, V, F, **copy)
    options.relative_eta = 5e-4
    with pytest.raises(shellspace.InputError, match="give one of them"):
        shellspace.geodesic(V, V, F, **options)


def bent(V, amount=0.3):
    end = V.copy()
    end[:, 2] = amount * (V[:, 0] - 0.5) ** 2
    return end


def assert_read_only(array):
    assert isinstance(array, np.ndarray)
    assert not array.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        array[(0,) * array.ndim] = 1.0
    # Not undone by setflags: the memory is not the array's own.
    with pytest.raises(ValueError, match="WRITEABLE"):
        array.setflags(write=True)


def test_result_arrays_are_read_only():
    V, F = plate()
    end = bent(V)
    run = shellspace.geodesic(V, end, F, steps=2, quiet=True)
    assert_read_only(run.path)
    path, _ = run
    assert_read_only(path)
    assert path is run.path
    scratch = path.copy()  # the twin: a copy is the caller's to write
    scratch[0, 0, 0] = 1.0
    log = shellspace.log(V, end, F, steps=2, quiet=True)
    assert_read_only(log.log)
    assert_read_only(log.path)
    shot = shellspace.shoot(V, end, F, steps=2, quiet=True,
                            allow_unconverged=True)
    assert_read_only(shot.path)
    moved = shellspace.transport(path, bent(V, 0.35), F, quiet=True,
                                 allow_unconverged=True)
    assert_read_only(moved.shapes)
    mean = shellspace.mean([V, end], F, quiet=True)
    assert_read_only(mean.mean)
    model = shellspace.pca([V, end, bent(V, -0.3)], F, modes=1, quiet=True,
                           allow_unconverged=True)
    assert_read_only(model.mean)
    assert model.shapes and all(not a.flags.writeable
                                for a in model.shapes.values())
    u, _ = shellspace.branching_simulate(nx=8, ny=32, continuation=1,
                                         allow_unconverged=True)
    assert_read_only(u)
    # Arrays that are not results stay the caller's: read_mesh, gradients.
    assert shellspace.energy_gradient(V, end, F).flags.writeable


def test_branching_simulate_raises_what_the_cli_exits_four_for():
    # Two LM iterations per stage: the last stage stops short, as the CLI's
    # `branching simulate --lm_iterations 2` (exit 4).
    with pytest.raises(shellspace.NotConvergedError,
                       match="the last stage ended"):
        shellspace.branching_simulate(nx=8, ny=32, continuation=1,
                                      lm_iterations=2)
    u, summary = shellspace.branching_simulate(
        nx=8, ny=32, continuation=1, lm_iterations=2, allow_unconverged=True)
    assert summary["converged"] is False
    # The twin: enough iterations, converged, no error.
    u, summary = shellspace.branching_simulate(nx=8, ny=32, continuation=1,
                                               lm_iterations=200)
    assert summary["converged"] is True


def test_a_film_strip_too_large_is_refused_before_drawing(tmp_path):
    V, F = plate()
    frames = [V] * 600
    target = tmp_path / "strip.png"
    with pytest.raises(shellspace.InputError,
                       match=r"write_film_strip: a film strip of 600 "
                             r"frame\(s\), 49152 x 824000 pixels .*needs about"):
        shellspace.write_film_strip(str(target), frames, F, width=49152,
                                    height=8192)
    assert not target.exists()
    with pytest.raises(shellspace.InputError, match="png: a film strip of "
                                                    "100001 frame"):
        shellspace.shoot(V, bent(V), F, steps=100000, png=str(target),
                         quiet=True)
    assert not target.exists()
    # The twin: a small strip is drawn.
    shellspace.write_film_strip(str(target), [V, bent(V)], F, width=64)
    assert target.exists()


def test_solve_modulo_rigid_motions_does_what_its_docstring_says():
    doc = shellspace.solve_modulo_rigid_motions.__doc__
    V, F = plate(4)
    end = bent(V)
    rows, cols, vals = shellspace.energy_hessian(V, end, F)
    rhs = shellspace.energy_gradient(V, end, F)
    # rhs is #V x 3; a flat 3#V vector is refused, as the docstring says.
    assert "rhs: the right-hand side, #V x 3" in doc
    assert "3#V or" not in doc
    p, positive = shellspace.solve_modulo_rigid_motions(rows, cols, vals,
                                                        rhs, end, 1e-6)
    assert p.shape == V.shape and np.all(np.isfinite(p))
    with pytest.raises(shellspace.InputError, match="rhs"):
        shellspace.solve_modulo_rigid_motions(rows, cols, vals, rhs.ravel(),
                                              end)
    # Indices outside [0, 3#V) and a negative shift: InputError.
    assert "integers in [0, 3#V)" in doc
    with pytest.raises(shellspace.InputError, match="outside"):
        shellspace.solve_modulo_rigid_motions(rows + 3 * len(V), cols, vals,
                                              rhs, end)
    assert "(finite, >= 0)" in doc
    with pytest.raises(shellspace.InputError, match="shift"):
        shellspace.solve_modulo_rigid_motions(rows, cols, vals, rhs, end, -1)
    # H = 0: not positive definite, as documented.
    z, positive = shellspace.solve_modulo_rigid_motions(
        rows, cols, 0 * vals, rhs, end)
    assert not positive
