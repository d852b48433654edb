"""The pairwise jobs of a collection: the geodesic distance matrix (with its
resumable cache), the geodesics of given pairs, and a detail transferred
onto every shape."""
import hashlib
import math
import os

import numpy as np

import shellspace
from .scheduling import (OK, PENDING, NOT_CONVERGED, INPUT_ERROR, ERROR, LOST,
                         RETRIED, Stopped, BlasThreads, Clock, Progress,
                         check_collection, check_counts, check_eta_pair,
                         check_real, check_shape, deadline_of, one_line,
                         run_tasks, solve_options, status_of,
                         write_npz_atomically)

CACHE_VERSION = 2  # 2: cpu_seconds


def geodesic_task(shapes, F, i, j, options, fail=()):
    """One pair: (i, j, status, E_K, message, (wall, cpu) seconds, path or
    None). `options`: geodesic keywords, plus blas_threads and return_path.
    `fail`: pairs that raise on purpose (a test's injected failure)."""
    options, blas_threads = solve_options(options)
    return_path = options.pop("return_path", False)
    clock = Clock()
    try:
        if (i, j) in fail:
            raise RuntimeError(f"injected failure of pair ({i}, {j})")
        with BlasThreads(blas_threads):
            path, summary = shellspace.geodesic(shapes[i], shapes[j], F,
                                                **options)
        return (i, j, OK, float(summary["path_energy"]), "",
                clock.seconds(), path if return_path else None)
    except Exception as error:  # reported in the pair's cell
        energy = (getattr(error, "summary", None) or {}).get("path_energy")
        return (i, j, status_of(error),
                math.nan if energy is None else float(energy),
                one_line(error), clock.seconds(), None)


class DistanceMatrix:
    """distances (N x N, NaN where a pair failed or is pending), energies
    (E_K of the pair's path, also of an unconverged one when known), status
    (int8 codes: OK ... LOST), messages {(i, j): one line}, seconds and
    cpu_seconds (per pair, wall and CPU time of its task: information
    only), computed (pairs solved by this call)."""

    def __init__(self, n):
        self.distances = np.full((n, n), np.nan)
        self.energies = np.full((n, n), np.nan)
        self.status = np.full((n, n), PENDING, dtype=np.int8)
        self.seconds = np.full((n, n), np.nan)
        self.cpu_seconds = np.full((n, n), np.nan)
        np.fill_diagonal(self.distances, 0.0)
        np.fill_diagonal(self.energies, 0.0)
        np.fill_diagonal(self.status, OK)
        self.messages = {}
        self.computed = 0

    def set(self, i, j, status, energy, message, seconds):
        """seconds: (wall, cpu) of the pair's task."""
        for a, b in ((i, j), (j, i)):
            self.status[a, b] = status
            self.energies[a, b] = energy
            self.seconds[a, b], self.cpu_seconds[a, b] = seconds
            self.distances[a, b] = (math.sqrt(energy) if status == OK
                                    else math.nan)
        if message:
            self.messages[(i, j)] = message
        else:
            self.messages.pop((i, j), None)

    def failed_pairs(self):
        i, j = np.nonzero(np.triu(self.status != OK, 1))
        return list(zip(i.tolist(), j.tolist()))

    def arrays(self):
        keys = sorted(self.messages)
        return dict(distances=self.distances, energies=self.energies,
                    status=self.status, seconds=self.seconds,
                    cpu_seconds=self.cpu_seconds,
                    message_pairs=np.array(keys, dtype=np.int64).reshape(-1, 2),
                    message_texts=np.array([self.messages[k] for k in keys],
                                           dtype=str))


def _digest(shapes, F, options):
    h = hashlib.sha256()
    for array in (np.ascontiguousarray(shapes, dtype=np.float64),
                  np.ascontiguousarray(F, dtype=np.int64)):
        h.update(repr(array.shape).encode())
        h.update(array.tobytes())
    h.update(repr(sorted(options.items())).encode())
    return h.hexdigest()


def _load_cache(path, n, digest):
    """The cached matrix of these shapes and options (an empty one without
    a cache file); an InputError for a cache of anything else."""
    result = DistanceMatrix(n)
    if path is None or not os.path.exists(path):
        return result
    try:
        with np.load(path, allow_pickle=False) as data:
            if int(data["version"]) != CACHE_VERSION or \
                    str(data["digest"]) != digest:
                raise shellspace.InputError(
                    f"cache {path} holds another data set or other options "
                    "(remove it or give another --cache)")
            for name in ("distances", "energies", "status", "seconds",
                         "cpu_seconds"):
                getattr(result, name)[...] = data[name]
            for (i, j), text in zip(data["message_pairs"].tolist(),
                                    data["message_texts"].tolist()):
                result.messages[(i, j)] = text
    except shellspace.InputError:
        raise
    except Exception as error:  # BadZipFile, EOFError, a foreign .npz, ...
        text = str(error).splitlines()[0] if str(error) else ""
        raise shellspace.InputError(
            f"cache {path} is not a distance cache (corrupt or another "
            f"file: {type(error).__name__}{': ' + text if text else ''}); "
            "remove it or give another --cache") from None
    return result


def distance_matrix(shapes, F, client=None, steps=4, cache=None,
                    batch_size=None, progress=False, time_limit=None,
                    pair_time_limit=None, threads=1, blas_threads=1,
                    retry_failed=False, fail_pairs=(), **geodesic_kwargs):
    """All pairwise geodesic distances sqrt(E_K) of `shapes` (N x #V x 3,
    one connectivity F): a DistanceMatrix.

    client: None (in-process) or a dask.distributed.Client. steps: K.
    cache: an .npz path, written atomically after every batch_size finished
    pairs (default: N(N-1)/2 / 50, at least 1) and at the end; the pairs it
    holds finished are not computed again (retry_failed=True: the failed
    ones are). time_limit: seconds for the whole matrix, then the finished
    pairs are returned (and cached), the others PENDING. pair_time_limit:
    each solve's time_limit (a pair it stops is PAIR_TIME_LIMIT, retried on
    resume). progress: True (a counter on stderr) or a callable(done,
    total, failed). threads, blas_threads: fixed per task (the digits do
    not depend on the workers). Other keywords go to shellspace.geodesic
    (tolerance, max_iterations, mask, mu, ...; allow_unconverged=False:
    an unconverged pair is NOT_CONVERGED with NaN distance)."""
    shapes, F = check_collection(shapes, F)
    n = shapes.shape[0]
    check_counts(steps=steps, threads=threads, blas_threads=blas_threads,
                 batch_size=batch_size, optional=("batch_size",))
    check_eta_pair(geodesic_kwargs)
    deadline = deadline_of(time_limit)
    deadline_of(pair_time_limit, "pair_time_limit")
    options = dict(geodesic_kwargs, steps=steps, threads=threads, quiet=True,
                   time_limit=pair_time_limit, blas_threads=blas_threads)
    digest = _digest(shapes, F, {k: v for k, v in options.items()
                                 if k != "time_limit"})
    result = _load_cache(cache, n, digest)
    redo = RETRIED + ((NOT_CONVERGED, INPUT_ERROR, ERROR) if retry_failed
                      else ())
    todo = [(i, j) for i in range(n) for j in range(i + 1, n)
            if result.status[i, j] in redo]
    batch_size = batch_size or max(1, (n * (n - 1) // 2) // 50)
    counter = Progress(progress, len(todo), "distances")
    since_write = [0]

    def save():
        if cache is not None:
            write_npz_atomically(cache, version=CACHE_VERSION, digest=digest,
                                 **result.arrays())

    def on_result(item):
        if item[0] == "lost":
            (i, j), message = item[1], item[2]
            result.set(i, j, LOST, math.nan, message, (math.nan, math.nan))
        else:
            i, j, status, energy, message, seconds, _ = item
            result.set(i, j, status, energy, message, seconds)
        result.computed += 1
        counter.step(result.status[i, j] != OK)
        since_write[0] += 1
        if since_write[0] >= batch_size:
            save()
            since_write[0] = 0

    try:
        left = run_tasks(geodesic_task, todo, shapes, F, client, on_result,
                         ("deadline", deadline), options, (tuple(fail_pairs),))
    except Stopped as stop:
        stop.partial = result
        raise
    finally:
        save()
    for i, j in left:
        result.messages[(i, j)] = "not computed: the time limit came first"
    return result


def map_geodesics(shapes, F, pairs, client=None, steps=4, progress=False,
                  threads=1, blas_threads=1, **geodesic_kwargs):
    """The discrete geodesics between shapes[i] and shapes[j] for (i, j) in
    pairs, one task each: a list of (status, path or None, E_K, message) in
    the order of pairs."""
    shapes, F = check_collection(shapes, F)
    check_counts(steps=steps, threads=threads, blas_threads=blas_threads)
    pairs = [(int(i), int(j)) for i, j in pairs]
    for i, j in pairs:
        if not (0 <= i < len(shapes) and 0 <= j < len(shapes)):
            raise shellspace.InputError(
                f"pair ({i}, {j}) outside 0..{len(shapes) - 1}")
    options = dict(geodesic_kwargs, steps=steps, threads=threads, quiet=True,
                   blas_threads=blas_threads, return_path=True)
    found = {}
    counter = Progress(progress, len(pairs), "geodesics")

    def on_result(item):
        if item[0] == "lost":
            found[item[1]] = (LOST, None, math.nan, item[2])
        else:
            i, j, status, energy, message, _, path = item
            found[(i, j)] = (status, path, energy, message)
        counter.step(item[0] == "lost" or item[2] != OK)

    run_tasks(geodesic_task, sorted(set(pairs)), shapes, F, client,
              on_result, None, options)
    return [found[p] for p in pairs]


def transfer_task(shapes, F, source, detail, j, options):
    """The detail (detail - shapes[source]) carried to shapes[j] along their
    geodesic by Schild's ladder (`transport`): (j, status, shape, message)."""
    options, blas_threads = solve_options(options)
    epsilon = options.pop("epsilon", 1.0)
    try:
        with BlasThreads(blas_threads):
            path, _ = shellspace.geodesic(shapes[source], shapes[j], F,
                                          **options)
            moved, _ = shellspace.transport(
                path, detail, F, epsilon=epsilon,
                **{k: v for k, v in options.items()
                   if k not in ("steps", "mask", "multires", "linear_solver",
                                "lm")})
        return (j, OK, moved[-1], "")
    except Exception as error:
        return (j, status_of(error), None, one_line(error))


def transfer(detail, source, shapes, F, client=None, steps=4, epsilon=1.0,
             progress=False, threads=1, blas_threads=1, **solver_kwargs):
    """The detail of `detail` (a #V x 3 shape: detail - shapes[source]) onto
    every shape: for each j the geodesic shapes[source] -> shapes[j] and the
    detail transported along it (Schild's ladder, `transport`), one task
    each. Returns a list of (status, shape or None, message); the source's
    own entry is `detail`."""
    shapes, F = check_collection(shapes, F)
    detail = check_shape("detail", detail, shapes, F)
    check_counts(steps=steps, threads=threads, blas_threads=blas_threads)
    check_counts(minimum=0, source=source)
    check_real("epsilon", epsilon)
    if not 0 <= source < len(shapes):
        raise shellspace.InputError(f"source {source} outside the shapes")
    options = dict(solver_kwargs, steps=steps, threads=threads, quiet=True,
                   blas_threads=blas_threads, epsilon=epsilon)
    found = {source: (OK, detail.copy(), "")}
    targets = [j for j in range(len(shapes)) if j != source]
    counter = Progress(progress, len(targets), "transfer")

    def on_result(item):
        if item[0] == "lost":
            found[item[1][0]] = (LOST, None, item[2])
            counter.step(True)
        else:
            j, status, shape, message = item
            found[j] = (status, shape, message)
            counter.step(status != OK)

    run_tasks(transfer_task, [(source, detail, j) for j in targets], shapes,
              F, client, on_result, None, options)
    return [found[j] for j in range(len(shapes))]
