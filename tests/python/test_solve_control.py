"""How the solving functions stop and say so (python/solve_control.h):
time_limit, KeyboardInterrupt between iterations with the partial result
attached, the CLI's up-front bounds of steps, and NotConvergedError unless
allow_unconverged=True.

The long solve of these tests is a shot of 100,000 EXP steps on the double
square (9 vertices; minutes if nothing stopped it, 244 MB by the CLI's
estimate): a stop ends it after the steps completed, and those frames are
the frames of a shot of that many steps, to the bit.
"""
import math
import os
import signal
import threading
import time

import numpy as np
import pytest

import shellspace
from boundary_table import CALLS, DATA, F, M, V, W

LONG_STEPS = 100000


def long_shoot(**kwargs):
    return shellspace.shoot(V, M, F, steps=LONG_STEPS, quiet=True, **kwargs)


def assert_prefix_of_a_full_shot(path):
    """A stopped shot's frames are those of an unstopped shot of as many
    steps: the stop changed no digit."""
    frames = path.shape[0]
    assert 2 <= frames < LONG_STEPS + 1
    full, _ = shellspace.shoot(V, M, F, steps=frames - 1, quiet=True,
                               allow_unconverged=True)
    assert np.array_equal(full, path)


class SigintAfter:
    """SIGINT to this process after `seconds`, from a timer thread, with
    Python's handler `handler` installed meanwhile."""

    def __init__(self, seconds, handler=signal.default_int_handler):
        self.seconds = seconds
        self.handler = handler

    def __enter__(self):
        self.previous = signal.signal(signal.SIGINT, self.handler)
        self.timer = threading.Timer(self.seconds, os.kill,
                                     (os.getpid(), signal.SIGINT))
        self.timer.start()
        return self

    def __exit__(self, *exc):
        self.timer.cancel()
        self.timer.join()
        signal.signal(signal.SIGINT, self.previous)
        return False


# ---- time_limit ----------------------------------------------------------

SOLVERS = {
    "geodesic": lambda **k: CALLS["geodesic"](None, **k),
    "log": lambda **k: CALLS["log"](None, **k),
    "shoot": lambda **k: CALLS["shoot"](None, **k),
    "transport": lambda **k: CALLS["transport"](None, **k),
    "spline": lambda **k: CALLS["spline"](None, **k),
    "regress": lambda **k: CALLS["regress"](None, **k),
    "mean": lambda **k: CALLS["mean"](None, **k),
    "pca": lambda **k: CALLS["pca"](None, **k),
    "branching_simulate": lambda **k: shellspace.branching_simulate(
        nx=8, ny=32, continuation=1, lm_iterations=30, **k),
}


@pytest.mark.parametrize("name", sorted(SOLVERS))
@pytest.mark.parametrize("limit", [-1.0, -1e-9, -math.inf, math.nan])
def test_a_negative_or_nan_time_limit_is_refused(name, limit):
    with pytest.raises(shellspace.InputError,
                       match=r"^time_limit must be >= 0 seconds"):
        SOLVERS[name](time_limit=limit)


@pytest.mark.parametrize("name", sorted(SOLVERS))
@pytest.mark.parametrize("limit", [0, 0.0, 1e10, 9.3e9, 1e300, math.inf])
def test_no_limit_values_run_to_the_same_digits(name, limit):
    # 0, inf and limits beyond the clock's range (1e10 s overflowed the
    # CLI's deadline) are no limit: not stopped, the same result.
    plain = SOLVERS[name]()
    limited = SOLVERS[name](time_limit=limit)
    summary = limited if isinstance(limited, dict) else limited[-1]
    assert summary["partial"] is False and summary["stop_reason"] == ""
    assert_same(limited, plain)


def assert_same(a, b):
    if hasattr(a, "to_dict"):  # a result: the pair (value, summary)
        assert type(a) is type(b)
        a, b = tuple(a), tuple(b)
    if isinstance(a, dict):
        assert set(a) == set(b)
        for k in a:
            if "seconds" not in k:
                assert_same(a[k], b[k])
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            assert_same(x, y)
    elif isinstance(a, np.ndarray):
        assert np.array_equal(a, b)
    else:
        assert a == b


def test_a_time_limit_stops_a_long_shot_with_the_frames_so_far():
    start = time.monotonic()
    with pytest.raises(shellspace.NotConvergedError) as error:
        long_shoot(time_limit=0.5)
    elapsed = time.monotonic() - start
    assert 0.5 <= elapsed < 10, elapsed
    e = error.value
    assert isinstance(e, RuntimeError)
    assert e.stop_reason == "time limit 0.5 s"
    assert str(e).startswith("shoot: stopped (time limit 0.5 s)")
    path, summary = e.result
    assert summary is e.summary
    assert summary["partial"] is True
    assert summary["stop_reason"] == "time limit 0.5 s"
    assert summary["frames"] == path.shape[0]
    assert_prefix_of_a_full_shot(path)
    # allow_unconverged=True: the same kind of result, returned.
    path, summary = long_shoot(time_limit=0.3, allow_unconverged=True)
    assert summary["partial"] is True
    assert_prefix_of_a_full_shot(path)


def test_a_time_limit_stops_pca_with_the_mean_alone(tmp_path):
    # A stop during the modes: the mean alone, as the CLI writes it.
    inputs = [V, M, W]
    shapes, summary = shellspace.pca(inputs, F, modes=1, quiet=True,
                                     max_exp_steps=16)
    assert "mode_1_plus" in shapes
    with pytest.raises(shellspace.NotConvergedError) as error:
        shellspace.pca(inputs, F, modes=1, quiet=True, time_limit=1e-9,
                       output=str(tmp_path / "pca"))
    shapes, summary = error.value.result
    assert list(shapes) == ["mean"]
    assert summary["partial"] and summary["modes"] == 0
    assert summary["stopped_in"] == "mean"
    assert sorted(os.listdir(tmp_path / "pca")) == ["mean.ply", "pca.json",
                                                    "summary.json"]


# ---- KeyboardInterrupt ---------------------------------------------------


def test_keyboard_interrupt_raises_with_the_partial_result():
    start = time.monotonic()
    with SigintAfter(0.5), pytest.raises(KeyboardInterrupt) as error:
        long_shoot()
    assert time.monotonic() - start < 10
    path, summary = error.value.result
    assert summary["partial"] is True and summary["stop_reason"] == "SIGINT"
    assert_prefix_of_a_full_shot(path)
    # Python's own handler is back in place: a SIGINT now is Python's.
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_keyboard_interrupt_writes_the_partial_frames(tmp_path):
    # As the CLI's SIGINT: the frames so far are written, then raised.
    with SigintAfter(0.5), pytest.raises(KeyboardInterrupt) as error:
        long_shoot(output=str(tmp_path / "out"))
    path, summary = error.value.result
    assert summary["output"] == str(tmp_path / "out")
    listing = os.listdir(tmp_path / "out")
    # The frames and, as the CLI writes it, the summary.
    assert "summary.json" in listing
    written = [name for name in listing if name.startswith("shape_")]
    assert len(written) == path.shape[0]
    assert len(listing) == path.shape[0] + 1
    # By frame number (shape_1000.ply sorts before shape_999.ply by name).
    last_name = max(written, key=lambda n: int("".join(filter(str.isdigit, n))))
    last, _ = shellspace.read_mesh(str(tmp_path / "out" / last_name))
    assert np.array_equal(last, path[-1])


def test_a_python_handler_that_does_not_raise_sees_the_signal():
    # The chain calls Python's handler: it runs once the solve ended, and
    # the solve stopped at the signal.
    seen = []
    with SigintAfter(0.5, lambda number, frame: seen.append(number)):
        path, summary = long_shoot(allow_unconverged=True)
    assert seen == [signal.SIGINT]
    assert summary["partial"] and summary["stop_reason"] == "SIGINT"
    assert_prefix_of_a_full_shot(path)


def test_an_ignored_sigint_does_not_stop_a_solve():
    with SigintAfter(0.2, signal.SIG_IGN):
        path, summary = long_shoot(time_limit=0.8, allow_unconverged=True)
    assert summary["stop_reason"] == "time limit 0.8 s"


def test_a_sigint_stops_a_solve_in_another_thread():
    # The poll reads the count of the chained handler on any thread; the
    # KeyboardInterrupt itself is the main thread's.
    out = {}

    def run():
        out["result"] = long_shoot(allow_unconverged=True)

    worker = threading.Thread(target=run)
    with SigintAfter(0.5):
        worker.start()
        with pytest.raises(KeyboardInterrupt):
            while worker.is_alive():
                time.sleep(0.01)
        worker.join()
    path, summary = out["result"]
    assert summary["stop_reason"] == "SIGINT"
    assert_prefix_of_a_full_shot(path)


# Long solves of other kinds, stopped inside their iterations: the LM and
# Newton iterations of a 400-step geodesic (its full solve: 20+ s), the
# L-BFGS of a 200-step spline; the result is the whole path, its ends the
# given shapes.
LONG = {
    "geodesic": (lambda **k: shellspace.geodesic(
        V, W, F, steps=400, quiet=True, tolerance=1e-12, **k), 401),
    "spline": (lambda **k: shellspace.spline(
        [V, M, W], [0, 100, 200], F, steps=200, quiet=True, tolerance=1e-12,
        **k), 201),
}


@pytest.mark.parametrize("name", sorted(LONG))
@pytest.mark.parametrize("stop", ["SIGINT", "time limit"])
def test_long_solves_stop_inside_their_iterations(name, stop):
    call, frames = LONG[name]
    start = time.monotonic()
    if stop == "SIGINT":
        with SigintAfter(0.5), pytest.raises(KeyboardInterrupt) as error:
            call()
        path, summary = error.value.result
    else:
        with pytest.raises(shellspace.NotConvergedError) as error:
            call(time_limit=0.3)
        path, summary = error.value.result
        assert error.value.stop_reason == "time limit 0.3 s"
    assert time.monotonic() - start < 10
    assert summary["partial"] is True
    assert summary["stop_reason"] == ("SIGINT" if stop == "SIGINT"
                                      else "time limit 0.3 s")
    assert summary["converged"] is False
    assert path.shape == (frames,) + V.shape
    assert np.array_equal(path[0], V) and np.array_equal(path[-1], W)


# ---- Bounds of steps -------------------------------------------------------

STEPS_BOUNDS = [
    ("shoot steps=10**9", lambda: shellspace.shoot(V, M, F, steps=10**9),
     r"steps must be <= 100000, got 1000000000"),
    ("shoot steps=100001", lambda: shellspace.shoot(V, M, F, steps=100001),
     r"steps must be <= 100000"),
    ("shoot steps=0", lambda: shellspace.shoot(V, M, F, steps=0),
     r"steps must be >= 1"),
    ("geodesic steps=100000", lambda: shellspace.geodesic(V, W, F,
                                                          steps=100000),
     r"^steps 100000 on 9 vertices needs about 1\.35e\+05 GB \(64 MB \+ "
     r"1500 B x #V x K\^2\), above the limit"),
    ("geodesic steps=10**9", lambda: shellspace.geodesic(V, W, F,
                                                         steps=10**9),
     r"steps must be <= 100000"),
    ("log steps=5000", lambda: shellspace.log(V, W, F, steps=5000),
     r"needs about 338 GB"),
    ("spline steps=10**6", lambda: shellspace.spline([V, W], [0, 2], F,
                                                     steps=10**6),
     r"steps must be <= 100000"),
    ("spline steps=1", lambda: shellspace.spline([V, W], [0, 1], F,
                                                 steps=1),
     r"steps must be >= 2"),
    ("regress steps=10**6", lambda: shellspace.regress([V, W], [0, 2], F,
                                                       steps=10**6),
     r"steps must be <= 100000"),
    ("pca log_steps=10**6", lambda: shellspace.pca([V, M, W], F, modes=1,
                                                   log_steps=10**6),
     r"log_steps must be <= 100000"),
    ("pca log_steps=10000", lambda: shellspace.pca([V, M, W], F, modes=1,
                                                   log_steps=10000),
     r"log_steps 10000 on 9 vertices needs about"),
    ("pca max_exp_steps=10**6", lambda: shellspace.pca(
        [V, M, W], F, modes=1, max_exp_steps=10**6),
     r"max_exp_steps must be <= 100000"),
    ("branching nx=4096 ny=8192", lambda: shellspace.branching_simulate(
        nx=4096, ny=8192), r"^nx 4096, ny 8192 \(33562624 nodes\) needs "
     r"about 101 GB \(16 MB \+ 3 KB x \(nx \+ 1\) x ny\)"),
]


@pytest.mark.parametrize("label,call,message", STEPS_BOUNDS,
                         ids=[c[0] for c in STEPS_BOUNDS])
def test_steps_are_bounded_up_front(label, call, message):
    start = time.monotonic()
    with pytest.raises(shellspace.InputError, match=message):
        call()
    assert time.monotonic() - start < 1


def test_steps_beyond_int_are_a_type_error():
    with pytest.raises(TypeError):
        shellspace.shoot(V, M, F, steps=2**31)


# ---- allow_unconverged -----------------------------------------------------

# Each stops at its iteration cap, short of its tolerance.
UNCONVERGED = {
    "geodesic": lambda **k: shellspace.geodesic(
        V, W, F, steps=4, max_iterations=1, tolerance=1e-12, quiet=True, **k),
    "log": lambda **k: shellspace.log(
        V, W, F, steps=4, max_iterations=1, tolerance=1e-12, quiet=True, **k),
    "mean": lambda **k: shellspace.mean(
        [V, W], F, max_iterations=1, tolerance=1e-12, quiet=True, **k),
    "spline": lambda **k: shellspace.spline(
        [V, M, W], [0, 2, 4], F, steps=4, max_iterations=1,
        tolerance=1e-12, quiet=True, **k),
    "regress": lambda **k: shellspace.regress(
        [V, W], [0, 4], F, steps=4, max_iterations=1, tolerance=1e-12,
        quiet=True, **k),
    "pca": lambda **k: shellspace.pca(
        [V, M, W], F, modes=1, max_iterations=1, tolerance=1e-12, quiet=True,
        **k),
    # EXP step 2 has no root (relative residual 2.0e-4): the CLI's
    # unsolved step.
    "shoot": lambda **k: shellspace.shoot(
        V, V + 0.6 * (W - V), F, steps=3, quiet=True, **k),
}


@pytest.mark.parametrize("name", sorted(UNCONVERGED))
def test_unconverged_raises_unless_allowed(name):
    with pytest.raises(shellspace.NotConvergedError) as error:
        UNCONVERGED[name]()
    e = error.value
    assert str(e).startswith(name + ": not converged: ")
    assert e.failures and e.stop_reason == ""
    assert e.result[-1] is e.summary
    assert e.summary["partial"] is False
    if name == "pca":
        assert e.summary["mean_converged"] is False
    elif name == "shoot":
        assert e.failures[0].startswith("EXP step 2 not solved")
    else:
        assert e.summary["converged"] is False
    # Allowed: returned, the very same result.
    assert_same(UNCONVERGED[name](allow_unconverged=True), e.result)


# The same calls with the default cap and tolerance: converged, returned.
CONVERGED = {
    "geodesic": lambda: shellspace.geodesic(V, W, F, steps=4, quiet=True),
    "log": lambda: shellspace.log(V, W, F, steps=4, quiet=True),
    "mean": lambda: shellspace.mean([V, W], F, quiet=True),
    "spline": lambda: shellspace.spline([V, M, W], [0, 2, 4], F, steps=4,
                                        quiet=True),
    "regress": lambda: shellspace.regress([V, W], [0, 2], F, steps=2,
                                          quiet=True),
    "pca": lambda: shellspace.pca([V, M, W], F, modes=1, quiet=True),
}


@pytest.mark.parametrize("name", sorted(CONVERGED))
def test_converged_runs_return(name):
    summary = CONVERGED[name]()[-1]
    assert summary["partial"] is False and summary["stop_reason"] == ""
    assert summary["mean_converged" if name == "pca" else "converged"]
