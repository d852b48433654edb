"""The Python front ends under the one output-path policy, with honest
stops: output=DIR as the CLI's --output DIR (replaced whole, summary.json),
outputs checked before any solve, a SIGALRM handler run during a solve,
and the collection verbs' refusals, corrupt caches, file modes, limits and
signals (one line, the partial result, exit 143 / 130)."""
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import shellspace
import shellspace.collections as sc
from procedural import plate
from process_signals import wait_until_signal_is_held


def pair(n=5):
    V, F = plate(n)
    B = V.copy()
    B[:, 2] = 0.2 * (B[:, 0] - 0.5) ** 2
    return V, B, F


def test_output_dir_is_replaced_whole_with_its_summary(tmp_path):
    V, B, F = pair()
    out = str(tmp_path / "out")
    shellspace.geodesic(V, B, F, steps=4, quiet=True, output=out)
    assert sorted(os.listdir(out)) == [f"shape_00{k}.ply" for k in range(5)] \
        + ["summary.json"]
    shellspace.geodesic(V, B, F, steps=2, quiet=True, output=out)
    assert sorted(os.listdir(out)) == [f"shape_00{k}.ply" for k in range(3)] \
        + ["summary.json"]
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    assert summary["steps"] == 2 if "steps" in summary else True
    assert summary["output"] == out
    # Nothing else beside it (no staging directory left).
    assert sorted(os.listdir(tmp_path)) == ["out"]


def test_outputs_are_checked_before_any_solve(tmp_path):
    V, B, F = pair()
    mesh = str(tmp_path / "a.ply")
    shellspace.write_mesh(mesh, V, F)
    notes = tmp_path / "mine"
    notes.mkdir()
    (notes / "notes.txt").write_text("keep")
    cases = [
        (dict(png=str(tmp_path / "x.glb"), gltf=str(tmp_path / "x.glb")),
         "same file"),
        (dict(png=str(tmp_path / "x.png"),
              gltf=str(tmp_path / "sub" / ".." / "x.png")), "same file"),
        (dict(gltf=str(tmp_path / "x.gltf")), "binary glTF"),
        (dict(output=str(notes)), "which no run writes"),
        (dict(output=str(tmp_path / "o"), png=str(tmp_path / "o" / "s.png")),
         "is inside output"),
        (dict(output=str(tmp_path / ("n" * 240))), "give a name of at most"),
        (dict(output=""), "empty path"),
        (dict(png=str(tmp_path / "s.jpg")), "a PNG image; name it .png"),
    ]
    (tmp_path / "sub").mkdir()
    for keywords, text in cases:
        start = time.monotonic()
        with pytest.raises(shellspace.InputError, match=text):
            shellspace.geodesic(V, B, F, steps=2, quiet=True, **keywords)
        assert time.monotonic() - start < 2
    with pytest.raises(shellspace.InputError, match="same file"):
        shellspace.spline([V, B], [0, 4], F, steps=4, quiet=True,
                          png=str(tmp_path / "y.png"),
                          gltf=str(tmp_path / "y.png"))
    with pytest.raises(shellspace.InputError, match="name it .png"):
        shellspace.write_film_strip(str(tmp_path / "s.jpg"), [V, B], F)
    with pytest.raises(shellspace.InputError, match="name it .ply, .obj"):
        shellspace.log(V, B, F, steps=2, quiet=True,
                       output=str(tmp_path / "l.stl"))
    assert (notes / "notes.txt").read_text() == "keep"
    assert sorted(os.listdir(tmp_path)) == ["a.ply", "mine", "sub"]


def test_a_mask_given_by_its_path_is_an_input(tmp_path):
    V, B, F = pair()
    mask = tmp_path / "m.png"
    mask.write_text("0\n4\n")
    alias = tmp_path / "alias.txt"
    os.link(mask, alias)
    calls = [
        lambda: shellspace.geodesic(V, B, F, steps=2, quiet=True,
                                    mask=str(mask), png=str(mask)),
        lambda: shellspace.geodesic(V, B, F, steps=2, quiet=True,
                                    mask=mask, png=str(alias)),
        lambda: shellspace.shoot(V, B, F, steps=2, quiet=True, mask=str(mask),
                                 png=str(tmp_path / "sub" / ".." / "m.png")),
        lambda: shellspace.log(V, B, F, steps=2, quiet=True, mask=str(alias),
                               output=str(mask)),
    ]
    (tmp_path / "sub").mkdir()
    for call in calls:
        with pytest.raises(shellspace.InputError,
                           match="is also the input mask"):
            call()
        assert mask.read_text() == "0\n4\n"
    assert sorted(os.listdir(tmp_path)) == ["alias.txt", "m.png", "sub"]
    # The twin: the same mask as indices is no file, and the call runs.
    shellspace.geodesic(V, B, F, steps=2, quiet=True, mask=[0, 4],
                        png=str(tmp_path / "s.png"))
    assert (tmp_path / "s.png").stat().st_size > 0


def test_a_sigalrm_handler_runs_during_a_solve():
    V, F = plate(24)
    B = V.copy()
    B[:, 2] = 0.6 * np.sin(3 * B[:, 0]) * (B[:, 1] - 0.5)

    class Alarm(Exception):
        pass

    def on_alarm(number, frame):
        raise Alarm()

    previous = signal.signal(signal.SIGALRM, on_alarm)
    try:
        signal.setitimer(signal.ITIMER_REAL, 0.3)
        start = time.monotonic()
        with pytest.raises(Alarm) as raised:
            shellspace.geodesic(V, B, F, steps=24, tolerance=1e-14,
                                max_iterations=10000, quiet=True,
                                threads=1)
        # During the solve, not after it: uninterrupted, 10,000 iterations
        # at about 0.2 s each. (Not a latency bound: on a loaded machine a
        # step took seconds.)
        assert time.monotonic() - start < 60
        assert hasattr(raised.value, "result")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


# ---- the collection verbs -------------------------------------------------

def shapes(count=3, n=5):
    V, F = plate(n)
    out = []
    for k in range(count):
        S = V.copy()
        S[:, 2] = 0.1 * k * (S[:, 0] - 0.5) ** 2
        out.append(S)
    return np.stack(out), F


@pytest.fixture()
def meshes(tmp_path):
    S, F = shapes()
    paths = []
    for k in range(len(S)):
        paths.append(str(tmp_path / f"s{k}.ply"))
        shellspace.write_mesh(paths[-1], S[k], F)
    return tmp_path, paths


def module(*args, **kwargs):
    return subprocess.run([sys.executable, "-m", "shellspace.collections",
                           *args], capture_output=True, text=True,
                          timeout=120, **kwargs)


def test_collection_outputs_that_are_inputs_are_refused(meshes):
    folder, paths = meshes
    os.link(paths[0], str(folder / "hard.ply"))
    before = open(paths[0], "rb").read()
    inputs = ",".join(paths)
    for output in (paths[0], str(folder / "sub" / ".." / "s0.ply"),
                   str(folder / "hard.ply"), "./" + os.path.relpath(
                       paths[1])):
        (folder / "sub").mkdir(exist_ok=True)
        run = module("mean", "--inputs", inputs, "--output", output)
        assert run.returncode == 1, run.stderr
        lines = run.stderr.strip().splitlines()
        assert len(lines) == 1 and "is also the input" in lines[0], run.stderr
    assert open(paths[0], "rb").read() == before
    run = module("distances", "--inputs", inputs + ",", "--output",
                 str(folder / "d.npz"))
    assert run.returncode == 1 and "empty item" in run.stderr
    run = module("distances", "--inputs", inputs, "--output",
                 str(folder / "d.npz"), "--cache", str(folder / "d.npz"))
    assert run.returncode == 1 and "same file" in run.stderr
    assert not os.path.exists(folder / "d.npz")


def test_a_corrupt_or_foreign_cache_is_one_line(meshes):
    folder, paths = meshes
    for content in (b"PK\x03\x04 not a zip", b"", b"\x93NUMPY garbage"):
        cache = folder / "c.npz"
        cache.write_bytes(content)
        run = module("distances", "--inputs", ",".join(paths), "--output",
                     str(folder / "d.npz"), "--cache", str(cache), "--quiet")
        assert run.returncode == 1, run.stderr
        lines = run.stderr.strip().splitlines()
        assert len(lines) == 1 and "not a distance cache" in lines[0], \
            run.stderr
        assert "Traceback" not in run.stderr
    # A FIFO as the cache: refused at once, not read (which would block).
    fifo = folder / "f.npz"
    os.mkfifo(fifo)
    run = module("distances", "--inputs", ",".join(paths), "--output",
                 str(folder / "d.npz"), "--cache", str(fifo), "--quiet")
    assert run.returncode == 1 and "not a regular file" in run.stderr, \
        run.stderr
    assert len(run.stderr.strip().splitlines()) == 1, run.stderr
    np.savez(str(folder / "c.npz"), other=np.zeros(3))
    with pytest.raises(shellspace.InputError, match="not a distance cache"):
        S, F = shapes()
        sc.distance_matrix(S, F, steps=2, cache=str(folder / "c.npz"))


def test_npz_outputs_follow_the_umask(meshes):
    folder, paths = meshes
    for mask, mode in ((0o022, 0o644), (0o002, 0o664)):
        out = folder / f"d{mask}.npz"
        run = module("distances", "--inputs", ",".join(paths), "--output",
                     str(out), "--quiet", "--steps", "2",
                     preexec_fn=lambda mask=mask: os.umask(mask))
        assert run.returncode == 0, run.stderr
        assert os.stat(out).st_mode & 0o777 == mode
        cache = str(out)[:-4] + ".cache.npz"
        assert os.stat(cache).st_mode & 0o777 == mode


def test_the_time_limit_stops_a_long_solve_in_process():
    # One pair of a few seconds (a 30 x 30 plate rolled by 2.5 rad,
    # K = 16), timed whole (the twin: it finishes); with a quarter of that
    # as the limit its geodesic is stopped at the limit (it was checked
    # only between pairs) and the pair stays pending.
    V, F = plate(30)
    B = V.copy()
    t = 2.5 * V[:, 0]
    B[:, 0], B[:, 2] = np.sin(t) / 2.5, (1 - np.cos(t)) / 2.5
    S = np.stack([V, B])
    start = time.monotonic()
    full = sc.distance_matrix(S, F, steps=16)
    whole = time.monotonic() - start
    assert full.status[0, 1] == sc.OK
    start = time.monotonic()
    limited = sc.distance_matrix(S, F, steps=16, time_limit=whole / 4)
    # The pending pair is the proof; the time allows 1 s for another
    # process taking the cores during one of the two runs (ctest -j).
    assert time.monotonic() - start < 0.75 * whole + 1.0
    assert limited.status[0, 1] == sc.PENDING


def test_limits_and_schedulers_are_checked():
    S, F = shapes()
    for limit in (-1, float("nan"), "5", True):
        with pytest.raises(shellspace.InputError, match="time_limit"):
            sc.distance_matrix(S, F, steps=2, time_limit=limit)
        with pytest.raises(shellspace.InputError, match="time_limit"):
            sc.elastic_mean(S, F, time_limit=limit)
    for steps in (True, 0, 2.0):
        with pytest.raises(shellspace.InputError, match="steps"):
            sc.distance_matrix(S, F, steps=steps)
    with pytest.raises(shellspace.InputError, match="modes"):
        sc.pca(S, F, modes=True)
    most = sc.most_local_workers()
    for bad in (f"local:{most + 1}", "local:1000", "local:0", "local:x",
                "local:", "host", "host:0", "host:70000", "tcp://",
                "a b:1", "tcp://tcp://h:1"):
        with pytest.raises(shellspace.InputError):
            sc._parse_scheduler(bad)
    assert sc._parse_scheduler("tcp://127.0.0.1:8786") == (
        "address", "tcp://127.0.0.1:8786")


def test_a_refused_scheduler_address_errors_within_5_s():
    pytest.importorskip("distributed")
    start = time.monotonic()
    with pytest.raises(shellspace.InputError, match="no scheduler answered"):
        sc._client_for("tcp://127.0.0.1:1")
    assert time.monotonic() - start < 8


def test_sigterm_and_sigint_write_the_partial_result(meshes, tmp_path):
    folder, _ = meshes
    S, F = shapes(count=6, n=12)
    paths = []
    for k in range(len(S)):
        paths.append(str(folder / f"big{k}.ply"))
        shellspace.write_mesh(paths[-1], S[k], F)
    for number, code in ((signal.SIGTERM, 143), (signal.SIGINT, 130)):
        out = folder / f"d{code}.npz"
        process = subprocess.Popen(
            [sys.executable, "-m", "shellspace.collections", "distances",
             "--inputs", ",".join(paths), "--output", str(out), "--steps",
             "8", "--tolerance", "1e-14", "--quiet"],
            stderr=subprocess.PIPE, text=True)
        # Until the module's main has installed its SIGTERM handler (with
        # its SIGINT one): before that a signal kills the interpreter or
        # raises KeyboardInterrupt (a fixed sleep failed on a loaded machine).
        wait_until_signal_is_held(process, signal.SIGTERM, ("SigCgt:",),
                                  required=True)
        time.sleep(1.0)  # into the solves
        process.send_signal(number)
        _, err = process.communicate(timeout=60)
        assert process.returncode == code, err
        lines = err.strip().splitlines()
        assert len(lines) == 1 and "stopped (" in lines[0], err
        assert "Traceback" not in err
        with np.load(out) as data:
            assert bool(data["partial"])
            assert np.any(data["status"] == sc.PENDING)


def test_module_flags_are_checked_in_one_line(meshes):
    # python3 -m shellspace.collections: a bad value or an unknown flag is
    # one line (argparse printed its usage text), counts and reals are
    # checked before anything is read (--max_iterations 0 ran with 200,
    # --tolerance -1 wrote a matrix of failed pairs), --bending is one of
    # the two models.
    folder, paths = meshes
    inputs = ",".join(paths)
    out = str(folder / "d.npz")
    cases = [
        (["distances", "--steps", "abc"], 2, "invalid int value"),
        (["mean", "--bogus", "1"], 2, "unrecognized arguments"),
        (["distances", "--bending", "foo"], 1, "unknown bending model"),
        (["distances", "--max_iterations", "0"], 1, "at least 1"),
        (["distances", "--tolerance", "-1"], 1, "--tolerance must be"),
        (["distances", "--mu", "nan"], 1, "--mu must be"),
        (["pca", "--modes", "0"], 1, "--modes must be at least 1"),
    ]
    for args, code, text in cases:
        output = out if args[0] != "mean" else str(folder / "m.ply")
        if args[0] == "pca":
            output = str(folder / "p.npz")
        run = module(*args, "--inputs", inputs, "--output", output)
        assert run.returncode == code, (args, run.stderr)
        lines = run.stderr.strip().splitlines()
        assert len(lines) == 1 and text in lines[0], (args, run.stderr)
        assert not os.path.exists(output)
