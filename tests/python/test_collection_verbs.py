"""The `shellspace collection` verbs (mean, pca, distances through the
CLI) on the procedural plates of test_collections.py: their files against
shellspace.collections in-process, their refusals in one line, a stop while
the verb starts Python, and failures said under --quiet.
"""
import os
import signal
import subprocess
import time

import numpy as np
import pytest

import shellspace
import shellspace.collections as sc
from procedural import bent_plates
from process_signals import wait_until_signal_is_held

SHAPES, F = bent_plates()
N = len(SHAPES)

CLI = os.environ.get("SHELLSPACE_CLI") or os.path.join(
    os.path.dirname(shellspace.__file__), os.pardir, "shellspace")


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    folder = tmp_path_factory.mktemp("collection")
    paths = []
    for k in range(N):
        paths.append(str(folder / f"s{k}.ply"))
        shellspace.write_mesh(paths[-1], SHAPES[k], F)
    return folder, ",".join(paths)


def run_cli(*args):
    if not os.path.exists(CLI):
        pytest.skip("no shellspace binary (SHELLSPACE_CLI)")
    return subprocess.run([CLI, "collection", *args], capture_output=True,
                          text=True, timeout=300)


def test_cli_collection_mean_and_pca(meshes):
    folder, inputs = meshes
    mean_path, model_path = str(folder / "M.ply"), str(folder / "P.npz")
    run = run_cli("mean", "--inputs", inputs, "--output", mean_path,
                  "--scheduler", "local:2", "--quiet")
    assert run.returncode == 0, run.stderr
    V, faces = shellspace.read_mesh(mean_path)
    assert np.array_equal(faces, F)
    expected = sc.elastic_mean(SHAPES, F)
    assert np.allclose(V, expected.mean, rtol=0, atol=1e-12)
    # A material flag reaches every term.
    run = run_cli("mean", "--inputs", inputs, "--output", mean_path,
                  "--eta", "0.5", "--quiet")
    assert run.returncode == 0, run.stderr
    stiffer = sc.elastic_mean(SHAPES, F, eta=0.5)
    assert np.allclose(shellspace.read_mesh(mean_path)[0], stiffer.mean,
                       rtol=0, atol=1e-12)
    assert np.abs(stiffer.mean - expected.mean).max() > 1e-4
    run = run_cli("pca", "--inputs", inputs, "--output", model_path,
                  "--modes", "2", "--quiet")
    assert run.returncode == 0, run.stderr
    model = sc.pca(SHAPES, F, modes=2)
    with np.load(model_path) as data:
        assert np.allclose(data["eigenvalues"], model.eigenvalues,
                           rtol=1e-6, atol=1e-12)
        assert list(data["mode_shape_names"]) == sorted(model.mode_shapes)
        assert np.array_equal(data["faces"], F)


@pytest.mark.parametrize("args, code, text", [
    (["distances", "--scheduler", "local:0"], 1, "worker count"),
    (["distances", "--scheduler", "no address"], 1, "scheduler address"),
    (["distances", "--steps", "0"], 1, "--steps must be"),
    (["distances", "--modes", "2"], 2, "not a flag of collection distances"),
    (["mean", "--steps", "2"], 2, "not a flag of collection mean"),
    (["pca", "--modes", "0"], 1, "--modes must be"),
    (["pca", "--modes", "5"], 1, "--modes must be in 1..4"),
    (["distances", "--time_limit", "-1"], 1, "--time_limit must be"),
    (["distances", "--output", "OUT.txt"], 1, "must end in .npz"),
    (["mean", "--output", "OUT.xyz"], 1, "must end in .ply"),
    (["distances", "--inputs", "MISSING"], 1, "cannot open mesh file"),
    (["mean", "--eta", "0.5", "--relative_eta", "0.1"], 1, "not both"),
    (["mean", "--bending", "edges"], 1, "unknown bending model"),
])
def test_cli_collection_refuses_bad_flags_in_one_line(meshes, args, code,
                                                      text):
    folder, inputs = meshes
    args = list(args)
    if "--inputs" in args:
        args[args.index("--inputs") + 1] = inputs.split(",")[0] + "," + str(
            folder / "missing.ply")
    else:
        args += ["--inputs", inputs]
    output = str(folder / ("OUT.ply" if args[0] == "mean" else "OUT.npz"))
    if "--output" in args:
        output = str(folder / args[args.index("--output") + 1])
        args[args.index("--output") + 1] = output
    else:
        args += ["--output", output]
    run = run_cli(*args)
    assert run.returncode == code
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and text in lines[0], run.stderr
    assert not os.path.exists(output)


def test_a_stop_while_the_cli_starts_python_is_one_line(meshes, tmp_path):
    # SIGINT / SIGTERM soon after `shellspace collection` execs the
    # interpreter (while it imports numpy and the module): one line, exit
    # 130 / 143, no traceback and no death by the signal. Before, a
    # KeyboardInterrupt traceback or exit -2.
    if not os.path.exists(CLI):
        pytest.skip("no shellspace binary (SHELLSPACE_CLI)")
    _, inputs = meshes
    for number, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
        for delay in (0.03, 0.08):
            run = subprocess.Popen(
                [CLI, "collection", "distances", "--inputs", inputs,
                 "--output", str(tmp_path / "d.npz"), "--quiet"],
                stderr=subprocess.PIPE, text=True)
            # From the moment the CLI handles or blocks the signal (before
            # that, the signal's default action ends any program: on a
            # loaded machine 30 ms did not reach it): then into python's
            # start-up.
            wait_until_signal_is_held(run, number)
            time.sleep(delay)
            run.send_signal(number)
            err = run.communicate(timeout=120)[1]
            if run.returncode == 0:
                continue  # finished first (a fast machine): nothing to see
            assert run.returncode == code, (delay, run.returncode, err)
            assert "Traceback" not in err, err
            assert len(err.strip().splitlines()) == 1, err
            assert "stopped (" in err, err


def test_cli_collection_failures_are_said_under_quiet(meshes):
    # --quiet drops the progress and the summary of a run that succeeds; a
    # run that does not (exit 4: the mean capped at one Newton step) still
    # says so in one line, as the C++ verbs do.
    folder, inputs = meshes
    run = run_cli("mean", "--inputs", inputs, "--output",
                  str(folder / "capped.ply"), "--max_iterations", "1",
                  "--quiet")
    assert run.returncode == 4, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "max iterations" in lines[0], run.stderr
    # The twin: a converged run under --quiet says nothing.
    run = run_cli("mean", "--inputs", inputs, "--output",
                  str(folder / "full.ply"), "--quiet")
    assert run.returncode == 0 and run.stderr == "", run.stderr
