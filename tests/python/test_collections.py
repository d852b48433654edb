"""shellspace.collections: the distance matrix in-process and on a Dask
LocalCluster (2 worker processes, 1 thread each), on procedural plates.

Each cell against an independent expectation (a direct shellspace.geodesic
of the pair), the cluster's matrix against the serial one bit for bit, a
worker killed while it runs tasks (the matrix unchanged), failing pairs in
their cells, and a resumed run that computes nothing twice.
"""
import os
import signal
import subprocess
import sys

import numpy as np
import pytest

import shellspace
import shellspace.collections as sc

STEPS = 2


def plate(n=6):
    """An n x n grid on the unit square, two triangles per cell."""
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
    V = np.stack([x.ravel(), y.ravel(), np.zeros(n * n)], axis=1)
    F = []
    for r in range(n - 1):
        for c in range(n - 1):
            a = r * n + c
            F += [[a, a + 1, a + n + 1], [a, a + n + 1, a + n]]
    return V, np.array(F, dtype=np.int64)


def collection(count=5, n=6):
    """The plate bent about y by a different amount and twisted a little."""
    V, F = plate(n)
    shapes = []
    for k in range(count):
        S = V.copy()
        S[:, 2] = 0.12 * k * (S[:, 0] - 0.5) ** 2 + 0.03 * k * (
            S[:, 0] - 0.5) * (S[:, 1] - 0.5)
        shapes.append(S)
    return np.stack(shapes), F


SHAPES, F = collection()
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
    shapes, faces = collection(count=6, n=14)  # 15 pairs of ~0.1 s
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
