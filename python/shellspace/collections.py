"""shellspace.collections: many independent solves over a collection of shapes
with one connectivity, in this process or on a Dask cluster.

    import shellspace.collections as sc
    result = sc.distance_matrix(shapes, F, steps=4)            # in-process
    result = sc.distance_matrix(shapes, F, client=client)      # on Dask
    result.distances, result.status, result.messages

The geodesic distance of a pair is sqrt(E_K) of its discrete geodesic
(E_K = K sum_k W[s_{k-1}, s_k], the path energy `geodesic` reports; for a
continuous geodesic E = L^2, and the discrete length sum_k sqrt(W) is at most
sqrt(E_K)). The pair (i, j), i < j, is solved from shape i to shape j and the
matrix is symmetric by that; the diagonal is 0.

Every pair is one task of the same pure function of (shapes, F, i, j,
options): the shapes are scattered to the workers once (broadcast), each task
fixes its thread counts (the solver's `threads`, the BLAS's `blas_threads`,
OpenMP serial), so the digits are those of the serial run whichever worker
or thread computes the pair, and a task that Dask reruns after a worker died
gives the same digits again. A pair that fails (InputError, NotConvergedError,
any exception, its workers lost) gets a status code and NaN distance in its
cell; the other pairs are unaffected. `cache=PATH.npz` makes a run
resumable: the finished pairs are written atomically after every batch and a
rerun with the same shapes and options computes only the others.

Command line (a front of distance_matrix):

    python3 -m shellspace.collections distances --inputs a.ply,b.ply,...
        [--scheduler local[:N]|ADDRESS] --output D.npz [--steps K]
        [--time_limit S] [--pair_time_limit S] [--cache C.npz]
"""
import argparse
import ctypes
import hashlib
import math
import os
import sys
import tempfile
import time

import numpy as np

import shellspace

# Status codes of a pair (the status matrix, int8).
OK = 0
PENDING = 1          # not computed (the run stopped first): retried on resume
NOT_CONVERGED = 2    # the solve missed its stopping criterion: NaN distance
PAIR_TIME_LIMIT = 3  # the pair's own time limit stopped it: retried on resume
INPUT_ERROR = 4      # shellspace.InputError (e.g. a degenerate shape)
ERROR = 5            # any other exception in the task
LOST = 6             # the task's workers died more often than Dask allows
STATUS_NAMES = {OK: "ok", PENDING: "pending", NOT_CONVERGED: "not converged",
                PAIR_TIME_LIMIT: "pair time limit", INPUT_ERROR: "input error",
                ERROR: "error", LOST: "lost"}
# Statuses a resumed run computes again (the others are final: the same
# task would give the same answer).
RETRIED = (PENDING, PAIR_TIME_LIMIT, LOST)

CACHE_VERSION = 2  # 2: cpu_seconds


# ---- thread counts of a task ----------------------------------------------

def _openblas():
    """The process's OpenBLAS (loaded with the module), or None."""
    try:
        with open("/proc/self/maps") as maps:
            paths = {line.split()[-1] for line in maps
                     if "libopenblas" in line.split()[-1]}
    except OSError:
        return None
    for path in sorted(paths):
        try:
            lib = ctypes.CDLL(path)
            lib.openblas_get_num_threads.restype = ctypes.c_int
            lib.openblas_set_num_threads.argtypes = [ctypes.c_int]
            return lib
        except (OSError, AttributeError):
            continue
    return None


def _serial_openmp():
    """This thread's OpenMP regions serial (nthreads 1, dynamic), as the
    module does for its importing thread (geometry/openmp_threads.h), also
    where Dask's workers set OMP_NUM_THREADS=1, which the module respects
    but which leaves CHOLMOD's num_threads(4) regions at 4 threads per
    worker."""
    try:
        with open("/proc/self/maps") as maps:
            paths = sorted({line.split()[-1] for line in maps
                            if "libgomp" in line.split()[-1]})
        if paths:
            gomp = ctypes.CDLL(paths[0])
            gomp.omp_set_num_threads(1)
            gomp.omp_set_dynamic(1)
    except (OSError, AttributeError):
        pass


class _BlasThreads:
    """OpenBLAS's thread count fixed for a block, restored after. The count
    changes the digits of the factorisations (cactus0 -> cactus1, K = 2:
    another path with 1 thread than with 2), so every task fixes it."""

    def __init__(self, threads):
        self.threads = threads
        self.lib = _openblas() if threads else None
        self.previous = None

    def __enter__(self):
        _serial_openmp()
        if self.lib is not None:
            self.previous = self.lib.openblas_get_num_threads()
            self.lib.openblas_set_num_threads(self.threads)
        return self

    def __exit__(self, *exc):
        if self.lib is not None and self.previous is not None:
            self.lib.openblas_set_num_threads(self.previous)
        return False


# ---- the tasks ------------------------------------------------------------

def _status_of(error):
    if isinstance(error, shellspace.NotConvergedError):
        stop = getattr(error, "stop_reason", None)
        return (PAIR_TIME_LIMIT if str(stop or "").startswith("time limit")
                else NOT_CONVERGED)
    if isinstance(error, shellspace.InputError):
        return INPUT_ERROR
    return ERROR


def _one_line(error):
    text = f"{type(error).__name__}: {error}"
    return text.splitlines()[0] if text else type(error).__name__


class _Clock:
    """Wall and CPU seconds of a task: CPU of the calling thread (the task
    runs its solve in it: one solver thread, one BLAS thread, serial
    OpenMP)."""

    def __init__(self):
        self.wall, self.cpu = time.perf_counter(), time.thread_time()

    def seconds(self):
        return (time.perf_counter() - self.wall, time.thread_time() - self.cpu)


def geodesic_task(shapes, F, i, j, options, fail=()):
    """One pair: (i, j, status, E_K, message, (wall, cpu) seconds, path or
    None). `options`: geodesic keywords, plus blas_threads and return_path.
    `fail`: pairs that raise on purpose (a test's injected failure)."""
    options = dict(options)
    blas_threads = options.pop("blas_threads", 1)
    return_path = options.pop("return_path", False)
    clock = _Clock()
    try:
        if (i, j) in fail:
            raise RuntimeError(f"injected failure of pair ({i}, {j})")
        with _BlasThreads(blas_threads):
            path, summary = shellspace.geodesic(shapes[i], shapes[j], F,
                                                **options)
        return (i, j, OK, float(summary["path_energy"]), "",
                clock.seconds(), path if return_path else None)
    except Exception as error:  # reported in the pair's cell
        summary = getattr(error, "summary", None) or {}
        energy = summary.get("path_energy")
        return (i, j, _status_of(error),
                math.nan if energy is None else float(energy),
                _one_line(error), clock.seconds(), None)


def transfer_task(shapes, F, source, detail, j, options):
    """The detail (detail - shapes[source]) carried to shapes[j] along their
    geodesic by Schild's ladder (`transport`): (j, status, shape, message)."""
    options = dict(options)
    blas_threads = options.pop("blas_threads", 1)
    epsilon = options.pop("epsilon", 1.0)
    try:
        with _BlasThreads(blas_threads):
            path, _ = shellspace.geodesic(shapes[source], shapes[j], F,
                                          **options)
            moved, _ = shellspace.transport(
                path, detail, F, epsilon=epsilon,
                **{k: v for k, v in options.items()
                   if k not in ("steps", "mask", "multires", "linear_solver",
                                "lm")})
        return (j, OK, moved[-1], "")
    except Exception as error:
        return (j, _status_of(error), None, _one_line(error))


# ---- running tasks in-process or on Dask ----------------------------------

class _Progress:
    """A counter on stderr (or a callable progress(done, total, failed))."""

    def __init__(self, progress, total, label):
        self.callback = progress if callable(progress) else None
        self.stderr = progress is True
        self.total, self.label, self.done, self.failed = total, label, 0, 0

    def step(self, failed):
        self.done += 1
        self.failed += bool(failed)
        if self.stderr:
            end = "\n" if self.done == self.total else ""
            print(f"\r{self.label}: {self.done}/{self.total} "
                  f"({self.failed} failed)", end=end, file=sys.stderr,
                  flush=True)
        if self.callback is not None:
            self.callback(self.done, self.total, self.failed)


def _run(function, items, shapes, F, client, on_result, time_limit, extra):
    """Calls function(shapes, F, *item, *extra) for every item, in-process
    (client None) or as one Dask task each with the shapes scattered once;
    on_result(result) on this thread as results arrive. Returns the items
    not finished (time_limit seconds passed)."""
    deadline = None if not time_limit else time.monotonic() + time_limit
    items = list(items)
    if client is None:
        for n, item in enumerate(items):
            if deadline is not None and time.monotonic() >= deadline:
                return items[n:]
            on_result(function(shapes, F, *item, *extra))
        return []
    from distributed import as_completed
    shapes_future = client.scatter(shapes, broadcast=True)
    faces_future = client.scatter(F, broadcast=True)
    futures = {}
    for item in items:
        future = client.submit(function, shapes_future, faces_future, *item,
                               *extra, pure=False)
        futures[future] = item
    pending = dict(futures)
    results = as_completed(list(futures))
    try:
        # Polled, so that the time limit can end the wait for a long task.
        while not results.is_empty():
            if deadline is not None and time.monotonic() >= deadline:
                break
            batch = results.next_batch(block=False)
            if not batch:
                time.sleep(0.02)
                continue
            for future in batch:
                item = pending.pop(future)
                try:
                    result = future.result()
                except Exception as error:  # KilledWorker, a cancelled task
                    result = ("lost", item, _one_line(error))
                on_result(result)
    finally:
        client.cancel(list(pending))
    return list(pending.values())


def _digest(shapes, F, options):
    h = hashlib.sha256()
    for array in (np.ascontiguousarray(shapes, dtype=np.float64),
                  np.ascontiguousarray(F, dtype=np.int64)):
        h.update(repr(array.shape).encode())
        h.update(array.tobytes())
    h.update(repr(sorted(options.items())).encode())
    return h.hexdigest()


def _write_npz_atomically(path, **arrays):
    directory = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(
        prefix=f".{os.path.basename(path)}.", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(handle, "wb") as out:
            np.savez(out, **arrays)
            out.flush()
            os.fsync(out.fileno())
        os.replace(temporary, path)
    except BaseException:
        if os.path.exists(temporary):
            os.unlink(temporary)
        raise


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


def _load_cache(path, n, digest):
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
            result.distances[...] = data["distances"]
            result.energies[...] = data["energies"]
            result.status[...] = data["status"]
            result.seconds[...] = data["seconds"]
            result.cpu_seconds[...] = data["cpu_seconds"]
            for (i, j), text in zip(data["message_pairs"].tolist(),
                                    data["message_texts"].tolist()):
                result.messages[(i, j)] = text
    except (KeyError, ValueError, OSError) as error:
        if isinstance(error, shellspace.InputError):
            raise
        raise shellspace.InputError(
            f"cache {path} is not a distance cache: {error}") from None
    return result


def _check_collection(shapes, F):
    try:
        shapes = np.array(shapes, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise shellspace.InputError(f"shapes: {error}") from None
    if shapes.ndim != 3 or shapes.shape[2] != 3 or shapes.shape[0] < 1:
        raise shellspace.InputError(
            f"shapes: expected N x #V x 3, got shape {shapes.shape}")
    if not np.all(np.isfinite(shapes)):
        raise shellspace.InputError("shapes: not all finite")
    F = np.asarray(F)
    if F.ndim != 2 or F.shape[1] != 3 or F.dtype.kind not in "iu":
        raise shellspace.InputError(
            f"F: expected #F x 3 integers, got {F.dtype} {F.shape}")
    return shapes, np.ascontiguousarray(F, dtype=np.int64)


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
    shapes, F = _check_collection(shapes, F)
    n = shapes.shape[0]
    options = dict(geodesic_kwargs, steps=steps, threads=threads, quiet=True,
                   time_limit=pair_time_limit, blas_threads=blas_threads)
    digest = _digest(shapes, F, {k: v for k, v in options.items()
                                 if k != "time_limit"})
    result = _load_cache(cache, n, digest)
    redo = RETRIED + ((NOT_CONVERGED, INPUT_ERROR, ERROR) if retry_failed
                      else ())
    todo = [(i, j) for i in range(n) for j in range(i + 1, n)
            if result.status[i, j] in redo]
    if batch_size is None:
        batch_size = max(1, (n * (n - 1) // 2) // 50)
    counter = _Progress(progress, len(todo), "distances")
    since_write = [0]

    def save():
        if cache is not None:
            _write_npz_atomically(cache, version=CACHE_VERSION,
                                  digest=digest, **result.arrays())

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
        left = _run(geodesic_task, todo, shapes, F, client, on_result,
                    time_limit, (options, tuple(fail_pairs)))
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
    shapes, F = _check_collection(shapes, F)
    pairs = [(int(i), int(j)) for i, j in pairs]
    for i, j in pairs:
        if not (0 <= i < len(shapes) and 0 <= j < len(shapes)):
            raise shellspace.InputError(
                f"pair ({i}, {j}) outside 0..{len(shapes) - 1}")
    options = dict(geodesic_kwargs, steps=steps, threads=threads, quiet=True,
                   blas_threads=blas_threads, return_path=True)
    found = {}
    counter = _Progress(progress, len(pairs), "geodesics")

    def on_result(item):
        if item[0] == "lost":
            key = item[1]
            found[key] = (LOST, None, math.nan, item[2])
        else:
            i, j, status, energy, message, _, path = item
            key = (i, j)
            found[key] = (status, path, energy, message)
        counter.step(found[key][0] != OK)

    _run(geodesic_task, sorted(set(pairs)), shapes, F, client, on_result,
         None, (options, ()))
    return [found[p] for p in pairs]


def transfer(detail, source, shapes, F, client=None, steps=4, epsilon=1.0,
             progress=False, threads=1, blas_threads=1, **solver_kwargs):
    """The detail of `detail` (a #V x 3 shape: detail - shapes[source]) onto
    every shape: for each j the geodesic shapes[source] -> shapes[j] and the
    detail transported along it (Schild's ladder, `transport`), one task
    each. Returns a list of (status, shape or None, message); the source's
    own entry is `detail`."""
    shapes, F = _check_collection(shapes, F)
    detail, _ = _check_collection([detail], F)
    detail = detail[0]
    if detail.shape != shapes[0].shape:
        raise shellspace.InputError("detail: not the shapes' vertex count")
    if not 0 <= source < len(shapes):
        raise shellspace.InputError(f"source {source} outside the shapes")
    options = dict(solver_kwargs, steps=steps, threads=threads, quiet=True,
                   blas_threads=blas_threads, epsilon=epsilon)
    found = {source: (OK, detail.copy(), "")}
    targets = [j for j in range(len(shapes)) if j != source]
    counter = _Progress(progress, len(targets), "transfer")

    def on_result(item):
        if item[0] == "lost":
            j = item[1][0]
            found[j] = (LOST, None, item[2])
        else:
            j, status, shape, message = item
            found[j] = (status, shape, message)
        counter.step(found[j][0] != OK)

    _run(transfer_task, [(source, detail, j) for j in targets], shapes, F,
         client, on_result, None, (options,))
    return [found[j] for j in range(len(shapes))]


# ---- the command line -----------------------------------------------------

def _client_for(scheduler):
    """(client, cluster or None) for local[:N] or a scheduler address; None
    for 'none' (in-process)."""
    if scheduler in (None, "", "none"):
        return None, None
    from distributed import Client, LocalCluster
    if scheduler == "local" or scheduler.startswith("local:"):
        workers = 2 if scheduler == "local" else int(scheduler[6:])
        if workers < 1:
            raise shellspace.InputError("--scheduler local:N needs N >= 1")
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1,
                               processes=True, dashboard_address=None)
        return Client(cluster), cluster
    return Client(scheduler), None


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python3 -m shellspace.collections",
        description="Solves over a collection of shapes with one "
                    "connectivity, in-process or on Dask.")
    verbs = parser.add_subparsers(dest="verb", required=True)
    d = verbs.add_parser("distances", help="the geodesic distance matrix")
    d.add_argument("--inputs", required=True,
                   help="comma-separated meshes (one connectivity)")
    d.add_argument("--output", required=True, help="the result, .npz")
    d.add_argument("--scheduler", default="none",
                   help="none (in-process), local[:N] (N worker processes, "
                        "default 2) or a scheduler address tcp://HOST:8786")
    d.add_argument("--steps", type=int, default=4)
    d.add_argument("--tolerance", type=float, default=1e-8)
    d.add_argument("--max_iterations", type=int, default=200)
    d.add_argument("--time_limit", type=float, default=None,
                   help="seconds for the whole matrix (then the finished "
                        "pairs are written, the others pending)")
    d.add_argument("--pair_time_limit", type=float, default=None)
    d.add_argument("--cache", default=None,
                   help="resumable .npz cache (default: OUTPUT.cache.npz)")
    d.add_argument("--quiet", action="store_true")
    args = parser.parse_args(argv)
    try:
        if not args.output.endswith(".npz"):
            raise shellspace.InputError("--output must end in .npz")
        paths = [p for p in args.inputs.split(",") if p]
        if len(paths) < 2:
            raise shellspace.InputError("--inputs needs at least 2 meshes")
        meshes = [shellspace.read_mesh(p) for p in paths]
        F = meshes[0][1]
        for p, (V, faces) in zip(paths, meshes):
            if faces.shape != F.shape or not np.array_equal(faces, F):
                raise shellspace.InputError(
                    f"{p}: another connectivity than {paths[0]}")
        shapes = np.stack([V for V, _ in meshes])
        cache = args.cache or args.output[:-4] + ".cache.npz"
        client, cluster = _client_for(args.scheduler)
        try:
            result = distance_matrix(
                shapes, F, client=client, steps=args.steps, cache=cache,
                progress=not args.quiet, time_limit=args.time_limit,
                pair_time_limit=args.pair_time_limit,
                tolerance=args.tolerance, max_iterations=args.max_iterations)
        finally:
            if client is not None:
                client.close()
            if cluster is not None:
                cluster.close()
        _write_npz_atomically(args.output, inputs=np.array(paths, dtype=str),
                              **result.arrays())
    except (shellspace.InputError, ValueError, OSError) as error:
        print(f"shellspace.collections: {error}", file=sys.stderr)
        return 1
    failed = result.failed_pairs()
    pending = [p for p in failed if result.status[p] == PENDING]
    if not args.quiet:
        print(f"distances: {len(paths)} shapes, "
              f"{len(paths) * (len(paths) - 1) // 2} pairs, "
              f"{result.computed} computed, {len(failed) - len(pending)} "
              f"failed, {len(pending)} pending -> {args.output}",
              file=sys.stderr)
    if pending:
        return 124
    return 4 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
