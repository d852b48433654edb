"""shellspace.collections: the distance matrix, transfer, the elastic mean
and PCA in-process and on a Dask LocalCluster (2 worker processes, 1
thread each), on procedural plates.

Each cell against an independent expectation (a direct shellspace.geodesic
of the pair), the cluster's matrix against the serial one bit for bit, a
worker killed while it runs tasks (the matrix unchanged), failing pairs in
their cells, and a resumed run that computes nothing twice; transfer
against geodesic + transport; the mean against shellspace.mean and PCA
against shellspace.pca, the same digits on the cluster, a worker killed
during PCA's LOGs. The `shellspace collection` verbs:
test_collection_verbs.py.
"""
import os
import signal
import subprocess
import sys

import numpy as np
import pytest

import shellspace
import shellspace.collections as sc
from procedural import bent_plates

STEPS = 2


SHAPES, F = bent_plates()
N = len(SHAPES)
PAIRS = N * (N - 1) // 2


@pytest.fixture(scope="module")
def serial():
    return sc.distance_matrix(SHAPES, F, steps=STEPS)


@pytest.fixture(scope="module")
def client():
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1,
                                       processes=True, dashboard_address=None)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


def test_each_cell_is_sqrt_of_the_pairs_path_energy(serial):
    assert serial.computed == PAIRS
    assert np.all(serial.status == sc.OK)
    assert np.array_equal(np.diag(serial.distances), np.zeros(N))
    for i in range(N):
        for j in range(i + 1, N):
            _, summary = shellspace.geodesic(SHAPES[i], SHAPES[j], F,
                                             steps=STEPS, threads=1,
                                             quiet=True)
            expected = np.sqrt(summary["path_energy"])
            assert serial.distances[i, j] == expected
            assert serial.distances[j, i] == expected
    # More bending, farther: the distances from shape 0 increase.
    assert np.all(np.diff(serial.distances[0]) > 0)


def test_cluster_matrix_equals_the_serial_one_bitwise(serial, client):
    result = sc.distance_matrix(SHAPES, F, client=client, steps=STEPS)
    assert result.computed == PAIRS
    assert np.array_equal(result.distances, serial.distances)
    assert np.array_equal(result.status, serial.status)


def test_a_killed_worker_changes_no_digit(serial, client):
    shapes, faces = bent_plates(count=6, n=14)  # 15 pairs of ~0.1 s
    reference = sc.distance_matrix(shapes, faces, steps=4)
    killed = {}

    def kill_a_busy_worker(done, total, failed):
        if killed:
            return
        busy = [w for w, keys in client.processing().items() if keys]
        worker = busy[0]
        killed.update(worker=worker, done=done,
                      tasks=len(client.processing()[worker]))
        pid = client.run(os.getpid, workers=[worker])[worker]
        os.kill(pid, signal.SIGKILL)

    before = set(client.scheduler_info()["workers"])
    result = sc.distance_matrix(shapes, faces, client=client, steps=4,
                                progress=kill_a_busy_worker)
    assert killed["done"] == 1 and killed["tasks"] >= 1
    assert np.array_equal(result.distances, reference.distances)
    assert np.all(result.status == sc.OK)
    client.wait_for_workers(2, timeout=60)
    after = set(client.scheduler_info()["workers"])
    assert killed["worker"] in before and killed["worker"] not in after


@pytest.mark.parametrize("use_cluster", [False, True])
def test_a_failing_pair_is_reported_in_its_cell(serial, client, use_cluster):
    result = sc.distance_matrix(SHAPES, F, steps=STEPS,
                                client=client if use_cluster else None,
                                fail_pairs=[(1, 3)])
    assert result.status[1, 3] == result.status[3, 1] == sc.ERROR
    assert np.isnan(result.distances[1, 3]) and np.isnan(result.distances[3, 1])
    assert "injected failure of pair (1, 3)" in result.messages[(1, 3)]
    others = result.status == sc.OK
    assert others.sum() == N * N - 2
    assert np.array_equal(result.distances[others], serial.distances[others])
    assert result.failed_pairs() == [(1, 3)]


def test_an_unconverged_pair_has_a_status_and_nan(serial):
    # One iteration cannot reach tolerance 1e-8 on a pair far apart; the
    # pair (0, 1) of identical-to-first-order shapes may, so only the
    # status of each cell is checked against its own geodesic.
    result = sc.distance_matrix(SHAPES, F, steps=STEPS, max_iterations=1)
    for i in range(N):
        for j in range(i + 1, N):
            try:
                shellspace.geodesic(SHAPES[i], SHAPES[j], F, steps=STEPS,
                                    threads=1, quiet=True, max_iterations=1)
                converged = True
            except shellspace.NotConvergedError:
                converged = False
            if converged:
                assert result.status[i, j] == sc.OK
            else:
                assert result.status[i, j] == sc.NOT_CONVERGED
                assert np.isnan(result.distances[i, j])
                assert np.isfinite(result.energies[i, j])
                assert "NotConvergedError" in result.messages[(i, j)]
    assert (result.status == sc.NOT_CONVERGED).sum() >= 2


def test_a_resumed_run_computes_only_the_rest(serial, tmp_path):
    cache = str(tmp_path / "d.cache.npz")

    class Stop(Exception):
        pass

    def stop_after_4(done, total, failed):
        if done == 4:
            raise Stop()

    with pytest.raises(Stop):
        sc.distance_matrix(SHAPES, F, steps=STEPS, cache=cache,
                           batch_size=2, progress=stop_after_4)
    with np.load(cache) as data:
        assert (data["status"][np.triu_indices(N, 1)] == sc.OK).sum() == 4
    resumed = sc.distance_matrix(SHAPES, F, steps=STEPS, cache=cache)
    assert resumed.computed == PAIRS - 4
    assert np.array_equal(resumed.distances, serial.distances)
    again = sc.distance_matrix(SHAPES, F, steps=STEPS, cache=cache)
    assert again.computed == 0
    assert np.array_equal(again.distances, serial.distances)
    assert sorted(os.listdir(tmp_path)) == ["d.cache.npz"]  # no temporaries


def test_ctrl_c_keeps_the_finished_pairs(serial, tmp_path):
    # A real SIGINT after the third pair, with no batch written yet: the
    # in-process matrix raises KeyboardInterrupt, its cache holds the 3
    # finished pairs, and a resumed run computes only the others, to the
    # same digits. (Python's own handler is set for the test: a process
    # started in the background by a non-interactive shell inherits SIGINT
    # ignored, and then Ctrl-C does nothing anywhere.)
    cache = str(tmp_path / "d.cache.npz")

    def interrupt_after_3(done, total, failed):
        if done == 3:
            os.kill(os.getpid(), signal.SIGINT)

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            sc.distance_matrix(SHAPES, F, steps=STEPS, cache=cache,
                               batch_size=100, progress=interrupt_after_3)
    finally:
        signal.signal(signal.SIGINT, previous)
    with np.load(cache) as data:
        assert (data["status"][np.triu_indices(N, 1)] == sc.OK).sum() == 3
    resumed = sc.distance_matrix(SHAPES, F, steps=STEPS, cache=cache)
    assert resumed.computed == PAIRS - 3
    assert np.array_equal(resumed.distances, serial.distances)


@pytest.mark.parametrize("change", ["shapes", "steps", "material"])
def test_a_cache_of_other_data_is_refused(serial, tmp_path, change):
    cache = str(tmp_path / "d.npz")
    sc.distance_matrix(SHAPES[:3], F, steps=STEPS, cache=cache)
    shapes, kwargs = SHAPES[:3], dict(steps=STEPS)
    if change == "shapes":
        shapes = SHAPES[1:4]
    elif change == "steps":
        kwargs["steps"] = STEPS + 1
    else:
        kwargs["mu"] = 2.0
    before = open(cache, "rb").read()
    with pytest.raises(shellspace.InputError, match="another data set"):
        sc.distance_matrix(shapes, F, cache=cache, **kwargs)
    assert open(cache, "rb").read() == before


@pytest.mark.parametrize("shapes, faces, match", [
    (SHAPES[:, :, :2], F, "N x #V x 3"),
    (np.where(np.arange(3) == 0, np.nan, SHAPES), F, "finite"),
    (SHAPES, F.astype(float), "integers"),
    ([[["a", "b", "c"]]], F, "shapes"),
])
def test_bad_collections_are_input_errors(shapes, faces, match):
    with pytest.raises(shellspace.InputError, match=match):
        sc.distance_matrix(shapes, faces)


def test_map_geodesics_returns_the_paths():
    found = sc.map_geodesics(SHAPES, F, [(0, 2), (3, 1)], steps=STEPS)
    for (i, j), (status, path, energy, message) in zip([(0, 2), (3, 1)],
                                                       found):
        expected, summary = shellspace.geodesic(SHAPES[i], SHAPES[j], F,
                                                steps=STEPS, threads=1,
                                                quiet=True)
        assert status == sc.OK and message == ""
        assert np.array_equal(path, expected)
        assert energy == summary["path_energy"]


def test_the_command_line_writes_the_matrix(serial, tmp_path):
    paths = []
    for k in range(3):
        paths.append(str(tmp_path / f"s{k}.ply"))
        shellspace.write_mesh(paths[-1], SHAPES[k], F)
    output = str(tmp_path / "D.npz")
    run = subprocess.run(
        [sys.executable, "-m", "shellspace.collections", "distances",
         "--inputs", ",".join(paths), "--output", output, "--steps",
         str(STEPS), "--quiet"], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    with np.load(output) as data:
        # The PLY round trip keeps the coordinates (float64 text or binary).
        assert np.allclose(data["distances"], serial.distances[:3, :3],
                           rtol=1e-9, atol=0)
        assert list(data["inputs"]) == paths
    bad = subprocess.run(
        [sys.executable, "-m", "shellspace.collections", "distances",
         "--inputs", paths[0] + "," + str(tmp_path / "missing.ply"),
         "--output", str(tmp_path / "E.npz")], capture_output=True,
        text=True, timeout=120)
    assert bad.returncode == 1
    assert len(bad.stderr.strip().splitlines()) == 1
    assert not os.path.exists(tmp_path / "E.npz")


# ---- transfer, the elastic mean and shell PCA -------------------------------

def detail_on(shape):
    """A ripple added to a shape (the detail transfer carries)."""
    D = shape.copy()
    D[:, 2] += 0.02 * np.sin(3 * np.pi * shape[:, 1]) * shape[:, 0]
    return D


def test_transfer_carries_the_detail_along_each_geodesic(client):
    detail = detail_on(SHAPES[0])
    serial = sc.transfer(detail, 0, SHAPES, F, steps=STEPS)
    assert [status for status, _, _ in serial] == [sc.OK] * N
    assert np.array_equal(serial[0][1], detail)
    for j in range(1, N):
        path, _ = shellspace.geodesic(SHAPES[0], SHAPES[j], F, steps=STEPS,
                                      threads=1, quiet=True)
        moved, _ = shellspace.transport(path, detail, F, threads=1,
                                        quiet=True)
        assert np.array_equal(serial[j][1], moved[-1])
        # The detail arrives: the moved shape is not the bare target.
        assert np.abs(serial[j][1] - SHAPES[j]).max() > 0.005
    on_cluster = sc.transfer(detail, 0, SHAPES, F, steps=STEPS, client=client)
    for (s1, a, _), (s2, b, _) in zip(serial, on_cluster):
        assert s1 == s2 and np.array_equal(a, b)


def diameter(shape):
    return np.linalg.norm(shape.max(axis=0) - shape.min(axis=0))


@pytest.fixture(scope="module")
def serial_mean():
    mean, summary = shellspace.mean(SHAPES, F, threads=1, quiet=True)
    return mean, summary


@pytest.mark.parametrize("tolerance, bound", [(1e-8, 1e-7), (1e-13, 1e-9)])
def test_elastic_mean_is_the_library_mean(serial_mean, tolerance, bound):
    mean, summary = serial_mean
    result = sc.elastic_mean(SHAPES, F, tolerance=tolerance)
    assert result.converged and result.termination == "converged"
    assert result.gradient_norm <= tolerance * max(
        1, result.initial_gradient_norm)
    # The same minimiser of sum_i W[S_i, s] (both aligned to shapes[0]).
    assert np.abs(result.mean - mean).max() <= bound * diameter(SHAPES[0])
    assert result.energy == pytest.approx(summary["energy"], rel=1e-9)
    # Its own gradient, from the library's derivative, vanishes (with the
    # bending weight of shapes[0], as the mean's: energy_gradient would
    # take each S_i's own).
    eta = shellspace.energy(SHAPES[0], SHAPES[0], F)["eta"]
    G = sum(shellspace.energy_gradient(S, result.mean, F, eta=eta)
            for S in SHAPES)
    assert np.abs(G).max() <= 1e-6 * result.initial_gradient_norm


def test_elastic_mean_on_a_cluster_is_the_same_digits(client):
    here = sc.elastic_mean(SHAPES, F, shapes_per_task=2)
    there = sc.elastic_mean(SHAPES, F, shapes_per_task=2, client=client)
    assert np.array_equal(here.mean, there.mean)
    assert np.array_equal(here.energies, there.energies)
    assert here.history == there.history and here.rounds == there.rounds
    # 5 shapes in tasks of 2: 3 tasks a round, summed in one tree.
    assert here.rounds == here.iterations + 1


def test_elastic_mean_material_and_bad_input():
    # A stiffer bending weight is another mean (eta resolved from shapes[0]
    # and passed to every term, as shellspace.mean does).
    mean, _ = shellspace.mean(SHAPES, F, eta=0.5, threads=1, quiet=True)
    result = sc.elastic_mean(SHAPES, F, eta=0.5, tolerance=1e-12)
    assert np.abs(result.mean - mean).max() <= 1e-9 * diameter(SHAPES[0])
    with pytest.raises(shellspace.InputError, match="unknown keyword"):
        sc.elastic_mean(SHAPES, F, steps=3)
    with pytest.raises(shellspace.InputError, match="shapes_per_task"):
        sc.elastic_mean(SHAPES, F, shapes_per_task=0)
    stopped = sc.elastic_mean(SHAPES, F, max_iterations=1)
    assert not stopped.converged and stopped.termination == "max iterations"


def swapped(name):
    return name.replace("minus", "@").replace("plus", "minus").replace(
        "@", "plus")


def test_pca_is_the_library_pca_at_the_same_mean(serial_mean):
    shapes, summary = shellspace.pca(SHAPES, F, modes=2, threads=1,
                                     quiet=True)
    mean = shapes["mean"]
    assert np.array_equal(mean, serial_mean[0])
    result = sc.pca(SHAPES, F, mean=mean, modes=2)
    assert np.all(result.status == sc.OK)
    expected = np.array(summary["eigenvalues"])
    assert result.eigenvalues[0] > 100 * result.eigenvalues[1] > 0
    # The library's model to round-off (the same LOGs, Gram matrix, modes
    # and shots).
    assert np.abs(result.eigenvalues - expected).max() <= 1e-12 * expected[0]
    # The modes are orthonormal in g(u, w) = 1/2 u^T D_2^2 W[mean, mean] w.
    eta = shellspace.energy(SHAPES[0], SHAPES[0], F)["eta"]
    rows, cols, vals = shellspace.energy_hessian(mean, mean, F, eta=eta)
    H = np.zeros((mean.size, mean.size))
    np.add.at(H, (rows, cols), vals)
    W = np.stack([w.ravel() for w in result.modes[:2]])
    assert np.allclose(0.5 * W @ H @ W.T, np.eye(2), atol=1e-9)
    # Mode shapes: the library's, each mode signed as the library signs it
    # (the other sign's shape is far).
    size = diameter(mean)
    for j in (1, 2):
        for side in ("minus", "plus"):
            name = f"mode_{j}_{side}"
            same = np.abs(result.mode_shapes[name] - shapes[name]).max()
            other = np.abs(result.mode_shapes[swapped(name)] -
                           shapes[name]).max()
            assert same <= 1e-12 * size < 1e-3 * size <= other


def test_pca_modes_are_the_gram_eigenpairs_in_the_hessian_metric():
    # pca_modes against the closed form on the client: Gamma = V H V^T /
    # (2 n), its eigenpairs by numpy, w_j = sum_i a_ij v_i / sqrt(n
    # lambda_j) with the largest |a_ij| positive.
    mean = SHAPES.mean(axis=0)
    V = np.random.default_rng(7).normal(scale=0.01, size=SHAPES.shape)
    eta = shellspace.energy(SHAPES[0], SHAPES[0], F)["eta"]
    gram, eigenvalues, modes = shellspace.pca_modes(mean, V, F, eta=eta)
    rows, cols, vals = shellspace.energy_hessian(mean, mean, F, eta=eta)
    H = np.zeros((mean.size, mean.size))
    np.add.at(H, (rows, cols), vals)
    flat = V.reshape(N, -1)
    expected = 0.5 * flat @ H @ flat.T / N
    assert np.abs(gram - expected).max() <= 1e-14 * np.abs(expected).max()
    values, vectors = np.linalg.eigh(expected)
    values, vectors = values[::-1], vectors[:, ::-1]
    assert np.abs(eigenvalues - values).max() <= 1e-13 * values[0]
    assert len(modes) == np.sum(values > 1e-10 * values[0])
    for j in range(N):
        a = vectors[:, j] * np.sign(vectors[np.abs(vectors[:, j]).argmax(), j])
        w = (a @ flat / np.sqrt(N * values[j])).reshape(mean.shape)
        assert np.abs(modes[j] - w).max() <= 1e-10 * np.abs(w).max()
        assert 0.5 * modes[j].ravel() @ H @ modes[j].ravel() == \
            pytest.approx(1, abs=1e-10)


def test_elastic_mean_is_equivariant_under_rigid_motions_of_the_inputs():
    # W is invariant under rigid motions of either argument: moving the
    # inputs other than the first leaves the mean (aligned to shapes[0])
    # where it was, and moving the first moves it along.
    theta = 0.7
    R = np.array([[np.cos(theta), -np.sin(theta), 0],
                  [np.sin(theta), np.cos(theta), 0], [0, 0, 1]])
    moved = SHAPES.copy()
    moved[1:] = SHAPES[1:] @ R.T + [0.3, -1.0, 2.0]
    here = sc.elastic_mean(SHAPES, F, tolerance=1e-12)
    there = sc.elastic_mean(moved, F, tolerance=1e-12)
    assert np.abs(there.mean - here.mean).max() <= 1e-10 * diameter(SHAPES[0])
    assert there.energy == pytest.approx(here.energy, rel=1e-10)
    first = SHAPES.copy()
    first[0] = SHAPES[0] @ R.T
    turned = sc.elastic_mean(first, F, tolerance=1e-12)
    assert np.abs(turned.mean - here.mean @ R.T).max() <= \
        1e-9 * diameter(SHAPES[0])


def test_pca_on_a_cluster_is_the_same_digits(client):
    here = sc.pca(SHAPES, F, modes=2)
    there = sc.pca(SHAPES, F, modes=2, client=client)
    assert np.array_equal(here.mean, there.mean)
    assert np.array_equal(here.eigenvalues, there.eigenvalues)
    for a, b in zip(here.modes, there.modes):
        assert np.array_equal(a, b)
    assert sorted(here.mode_shapes) == sorted(there.mode_shapes) == [
        "mode_1_minus", "mode_1_plus", "mode_2_minus", "mode_2_plus"]
    for name in here.mode_shapes:
        assert np.array_equal(here.mode_shapes[name], there.mode_shapes[name])


def test_pca_with_a_worker_killed_during_the_logs(client):
    shapes, faces = bent_plates(count=6, n=14)
    mean = sc.elastic_mean(shapes, faces, shapes_per_task=3).mean
    reference = sc.pca(shapes, faces, mean=mean, modes=2, mode_shapes=False)
    client.wait_for_workers(2, timeout=60)
    killed = {}

    def kill_a_busy_worker(done, total, failed):
        if killed:
            return
        busy = [w for w, keys in client.processing().items() if keys]
        if not busy:
            return
        killed.update(worker=busy[0], done=done)
        pid = client.run(os.getpid, workers=[busy[0]])[busy[0]]
        os.kill(pid, signal.SIGKILL)

    result = sc.pca(shapes, faces, mean=mean, modes=2, mode_shapes=False,
                    client=client, progress=kill_a_busy_worker)
    assert killed and killed["done"] < len(shapes)
    assert np.all(result.status == sc.OK)
    assert np.array_equal(result.eigenvalues, reference.eigenvalues)
    for a, b in zip(result.modes, reference.modes):
        assert np.array_equal(a, b)
    client.wait_for_workers(2, timeout=60)


@pytest.mark.parametrize("kwargs, match", [
    (dict(modes=5), "at most 4"),
    (dict(modes=0), "modes must be >= 1"),
    (dict(log_steps=0), "log_steps"),
    (dict(exp_steps=4, max_exp_steps=2), "max_exp_steps"),
    (dict(mean=np.zeros((3, 3))), "vertex count"),
])
def test_pca_refuses_bad_options(kwargs, match):
    with pytest.raises(shellspace.InputError, match=match):
        sc.pca(SHAPES, F, **kwargs)


# ---- shellspace collection VERB (the C++ CLI's front) ----------------------

# ctest sets SHELLSPACE_CLI; else the binary beside build/python.
def test_pca_stopped_before_any_log_returns_everything_pending():
    # A time limit that ends the run before its first LOG: every shape
    # PENDING, no mode, an empty Gram matrix (it raised ValueError from a
    # reshape of no displacements). The twin: without the limit, modes.
    mean = sc.elastic_mean(SHAPES, F).mean
    stopped = sc.pca(SHAPES, F, mean=mean, modes=1, time_limit=1e-9)
    assert stopped.pending
    assert list(stopped.status) == [sc.PENDING] * len(SHAPES)
    assert stopped.modes == [] and stopped.gram.shape == (0, 0)
    full = sc.pca(SHAPES, F, mean=mean, modes=1)
    assert not full.pending and len(full.modes) >= 1
