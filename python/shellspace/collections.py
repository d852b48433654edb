"""shellspace.collections: many independent solves over a collection of shapes
with one connectivity, in this process or on a Dask cluster.

    import shellspace.collections as sc
    result = sc.distance_matrix(shapes, F, steps=4)            # in-process
    result = sc.distance_matrix(shapes, F, client=client)      # on Dask
    result.distances, result.status, result.messages
    mean = sc.elastic_mean(shapes, F, client=client).mean  # shellspace.mean's
    model = sc.pca(shapes, F, client=client, mean=mean, modes=3)

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

Command line (`shellspace collection VERB` runs it too):

    python3 -m shellspace.collections distances|mean|pca
        --inputs a.ply,b.ply,... --output D.npz|M.ply|P.npz
        [--scheduler local[:N]|ADDRESS] [--time_limit S] [--quiet]
        distances: [--steps K] [--pair_time_limit S] [--cache C.npz]
        pca: [--modes m] [--log_steps K] [--exp_steps K] [--amplitude t]
"""
import argparse
import ctypes
import hashlib
import math
import os
import signal
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
    module does for its importing thread (runtime/openmp_threads.h), also
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

class Stopped(BaseException):
    """SIGTERM or SIGINT arrived while the command line ran a verb (its
    handlers raise this): `signal_name`, `exit_code` (143, 130) and, once a
    verb function passed it on, `partial` (its result so far)."""

    def __init__(self, number):
        super().__init__(signal.Signals(number).name)
        self.signal_name = signal.Signals(number).name
        self.exit_code = 128 + int(number)
        self.partial = None


class TimeLimitError(shellspace.NotConvergedError):
    """The time limit passed before anything could be computed (e.g. the
    scheduler had no workers)."""


def _deadline(time_limit, name="time_limit"):
    """The monotonic deadline of `time_limit` seconds (None or 0: none);
    a negative, NaN or non-number limit is an InputError."""
    if time_limit is None:
        return None
    if isinstance(time_limit, bool) or not isinstance(
            time_limit, (int, float, np.integer, np.floating)):
        raise shellspace.InputError(
            f"{name} must be a number of seconds, got "
            f"{type(time_limit).__name__}")
    if not time_limit >= 0:
        raise shellspace.InputError(
            f"{name} must be >= 0 seconds (0 or None: no limit), got "
            f"{time_limit}")
    if time_limit == 0 or math.isinf(time_limit):
        return None
    return time.monotonic() + float(time_limit)


def _check_count(name, value, minimum):
    """A count keyword: an int (not a bool) >= minimum."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise shellspace.InputError(
            f"{name} must be an integer, got {type(value).__name__} {value!r}")
    if value < minimum:
        raise shellspace.InputError(f"{name} must be >= {minimum}, got {value}")


def _read_only(*arrays):
    """The arrays of a result made read-only (writeable=False), as the
    module's results: copy() for a scratch array."""
    for array in arrays:
        if isinstance(array, np.ndarray):
            array.flags.writeable = False


def _check_counts(minimum=1, optional=(), **values):
    """_check_count of each keyword; those named in `optional` may be
    None."""
    for name, value in values.items():
        if value is None and name in optional:
            continue
        _check_count(name, value, minimum)


def _check_real(name, value, positive=True):
    """A real keyword: a number (not a bool), finite, > 0 (positive) or
    >= 0."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(
            value, (int, float, np.integer, np.floating)):
        raise shellspace.InputError(
            f"{name} must be a real number, got {type(value).__name__} "
            f"{value!r}")
    if not math.isfinite(value) or not (value > 0 if positive
                                        else value >= 0):
        raise shellspace.InputError(
            f"{name} must be finite and {'> 0' if positive else '>= 0'}, "
            f"got {value}")


def _await_workers(client, deadline):
    """True once `client`'s scheduler has a worker; False if `deadline`
    passed first; without a deadline an InputError after WORKERS_TIMEOUT
    seconds (tasks would wait for workers forever)."""
    try:
        if client.scheduler_info().get("workers"):
            return True
    except Exception:
        pass
    timeout = (WORKERS_TIMEOUT if deadline is None
               else max(0.0, deadline - time.monotonic()))
    try:
        client.wait_for_workers(1, timeout=timeout)
        return True
    except Exception:
        if deadline is not None:
            return False
        raise shellspace.InputError(
            f"the scheduler has no workers (none registered within "
            f"{WORKERS_TIMEOUT} s)") from None

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
    not finished (the deadline passed). `time_limit`: seconds, or a
    ("deadline", monotonic time) pair shared by the stages of a verb."""
    if isinstance(time_limit, tuple):
        deadline = time_limit[1]
    else:
        deadline = _deadline(time_limit)
    items = list(items)
    if client is None:
        for n, item in enumerate(items):
            if deadline is not None and time.monotonic() >= deadline:
                return items[n:]
            call_extra = extra
            if deadline is not None and function in _SOLVE_TASKS:
                # The solve itself stops at the deadline (its options' own
                # time_limit, if shorter, still holds); one stopped by it is
                # not finished.
                options = dict(extra[0])
                left = max(deadline - time.monotonic(), 1e-3)
                if options.get("time_limit") in (None, 0):
                    options["time_limit"] = left
                else:
                    options["time_limit"] = min(options["time_limit"], left)
                call_extra = (options,) + tuple(extra[1:])
            value = function(shapes, F, *item, *call_extra)
            if deadline is not None and time.monotonic() >= deadline:
                return items[n:]
            on_result(value)
        return []
    from distributed import as_completed
    if not _await_workers(client, deadline):
        return items
    shapes_future = client.scatter(shapes, broadcast=True, hash=False)
    faces_future = client.scatter(F, broadcast=True, hash=False)
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


def _umask():
    """The process's umask (read from /proc, else set and restored)."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _write_npz_atomically(path, **arrays):
    """Staged beside `path` and renamed into place, with the mode a new
    file gets (0666 less the umask; mkstemp's is 0600)."""
    directory = os.path.dirname(os.path.abspath(path))
    handle, temporary = tempfile.mkstemp(
        prefix=f".{os.path.basename(path)}.", suffix=".tmp", dir=directory)
    try:
        with os.fdopen(handle, "wb") as out:
            np.savez(out, **arrays)
            out.flush()
            os.fchmod(out.fileno(), 0o666 & ~_umask())
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
    except shellspace.InputError:
        raise
    except Exception as error:  # BadZipFile, EOFError, a foreign .npz, ...
        text = str(error).splitlines()[0] if str(error) else ""
        raise shellspace.InputError(
            f"cache {path} is not a distance cache (corrupt or another "
            f"file: {type(error).__name__}{': ' + text if text else ''}); "
            "remove it or give another --cache") from None
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
    _check_counts(steps=steps, threads=threads, blas_threads=blas_threads,
                  batch_size=batch_size, optional=("batch_size",))
    _check_eta_pair(geodesic_kwargs)
    deadline = _deadline(time_limit)
    _deadline(pair_time_limit, "pair_time_limit")
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
                    ("deadline", deadline), (options, tuple(fail_pairs)))
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
    shapes, F = _check_collection(shapes, F)
    _check_counts(steps=steps, threads=threads, blas_threads=blas_threads)
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
    _check_counts(steps=steps, threads=threads, blas_threads=blas_threads)
    _check_count("source", source, 0)
    _check_real("epsilon", epsilon)
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


# ---- the elastic mean and shell PCA ---------------------------------------
#
# The elastic mean of shellspace.mean is s_bar = argmin_s E(s), E(s) =
# sum_i W[S_i, s] (the inputs as references; the time-discrete mean with one
# step, E_1[S_i, s] = W[S_i, s]). Its terms are per shape: E, the gradient
# G = sum_i D_2 W[S_i, s] and the Hessian H = sum_i D_2^2 W[S_i, s]. Each
# outer step evaluates them at the current s as tasks of `shapes_per_task`
# shapes, sums the tasks' terms in a fixed binary tree (on the workers:
# only the sum comes back), and takes a Newton step on the client: H p = -G
# modulo rigid motions (shellspace.solve_modulo_rigid_motions), shifted to
# H + lambda I where H is not positive definite on the gauge's coordinates
# or p no descent direction; a trial s + p is accepted if it satisfies
# Armijo's condition on E or lowers |G|_2 without raising E beyond
# round-off (as the library's Newton finish), else lambda grows. Its fixed
# point is G(s_bar) = 0, the point the library's LM + Newton solve reaches
# (tests: to 1e-9 of the diameter on plates).

_MATERIAL_KEYS = ("mu", "lambda_", "eta", "relative_eta", "bending")


def _check_eta_pair(kwargs):
    """eta and relative_eta are one or the other (as the module's
    functions and the CLI's flags)."""
    if kwargs.get("eta") is not None and \
            kwargs.get("relative_eta") is not None:
        raise shellspace.InputError(
            "eta and relative_eta: give one of them (eta is absolute, "
            "relative_eta is multiplied by the first shape's area)")


def _material(shapes, F, kwargs):
    """The material keywords with eta resolved once from shapes[0] (as
    shellspace.mean and shellspace.pca do): energy_gradient and log would
    otherwise take it from their own first argument."""
    unknown = sorted(set(kwargs) - set(_MATERIAL_KEYS))
    if unknown:
        raise shellspace.InputError(
            f"unknown keyword(s): {', '.join(unknown)}")
    material = dict(kwargs)
    _check_eta_pair(material)
    if material.get("eta") is None:
        probe = shellspace.energy(shapes[0], shapes[0], F, **material)
        material["eta"] = float(probe["eta"])
    material.pop("relative_eta", None)
    return material


def _sum_triplets(parts, n3):
    """The sum of sparse matrices given as (rows, cols, vals), in order."""
    if all(np.array_equal(p[0], parts[0][0]) and
           np.array_equal(p[1], parts[0][1]) for p in parts[1:]):
        vals = parts[0][2].copy()  # one pattern (energy_hessian's, by F)
        for p in parts[1:]:
            vals += p[2]
        return parts[0][0], parts[0][1], vals
    rows = np.concatenate([p[0] for p in parts])
    cols = np.concatenate([p[1] for p in parts])
    vals = np.concatenate([p[2] for p in parts])
    unique, inverse = np.unique(rows * n3 + cols, return_inverse=True)
    summed = np.bincount(inverse, weights=vals, minlength=len(unique))
    return unique // n3, unique % n3, summed


def mean_terms_task(shapes, F, indices, s, material, hessian=True):
    """sum over i in indices of (W[S_i, s], D_2 W[S_i, s], D_2^2 W[S_i, s])
    as a dict: energies (one per shape, in order), gradient (#V x 3),
    hessian (triplets) or None, infeasible (a degenerate s)."""
    n3 = 3 * s.shape[0]
    energies, gradient, hessians = [], np.zeros_like(s), []
    with _BlasThreads(1):
        try:
            for i in indices:
                energies.append(float(shellspace.energy(
                    shapes[i], s, F, **material)["total"]))
                gradient += shellspace.energy_gradient(shapes[i], s, F,
                                                       **material)
                if hessian:
                    hessians.append(shellspace.energy_hessian(
                        shapes[i], s, F, **material))
        except shellspace.InputError as error:  # a degenerate trial
            return dict(infeasible=_one_line(error))
    return dict(energies=np.array(energies), gradient=gradient,
                hessian=_sum_triplets(hessians, n3) if hessian else None,
                infeasible=None)


def add_mean_terms(a, b):
    """Two tasks' terms (of consecutive index ranges) summed: a + b."""
    if a["infeasible"] or b["infeasible"]:
        return a if a["infeasible"] else b
    hessian = None
    if a["hessian"] is not None:
        hessian = _sum_triplets([a["hessian"], b["hessian"]],
                                3 * a["gradient"].shape[0])
    return dict(energies=np.concatenate([a["energies"], b["energies"]]),
                gradient=a["gradient"] + b["gradient"], hessian=hessian,
                infeasible=None)


class _Terms:
    """Evaluates the summed mean terms at s, in-process or on a client
    (the shapes scattered once); the same tasks and the same reduction tree
    either way, so the same digits."""

    def __init__(self, shapes, F, client, shapes_per_task, material):
        self.shapes, self.F, self.client = shapes, F, client
        n = len(shapes)
        self.chunks = [list(range(k, min(n, k + shapes_per_task)))
                       for k in range(0, n, shapes_per_task)]
        self.material = material
        self.rounds = 0
        if client is not None:
            self.shapes_future = client.scatter(shapes, broadcast=True,
                                                hash=False)
            self.faces_future = client.scatter(F, broadcast=True, hash=False)

    def __call__(self, s, hessian=True):
        self.rounds += 1
        if self.client is None:
            level = [mean_terms_task(self.shapes, self.F, c, s,
                                     self.material, hessian)
                     for c in self.chunks]
            while len(level) > 1:
                level = [add_mean_terms(*level[k:k + 2])
                         if k + 1 < len(level) else level[k]
                         for k in range(0, len(level), 2)]
            return level[0]
        s_future = self.client.scatter(s, broadcast=True, hash=False)
        level = [self.client.submit(mean_terms_task, self.shapes_future,
                                    self.faces_future, c, s_future,
                                    self.material, hessian, pure=False)
                 for c in self.chunks]
        while len(level) > 1:
            level = [self.client.submit(add_mean_terms, *level[k:k + 2],
                                        pure=False)
                     if k + 1 < len(level) else level[k]
                     for k in range(0, len(level), 2)]
        return level[0].result()


class ElasticMean:
    """mean (#V x 3, aligned rigidly to shapes[0]), energy (sum_i W[S_i,
    mean]), energies (W[S_i, mean]), gradient_norm (|G|_inf at the mean),
    gradient_target, initial_gradient_norm, converged, termination,
    iterations (outer steps, accepted or not), rounds (evaluations of the
    terms: one set of tasks each), history [(|G|_inf, E, shift,
    accepted)]."""


def elastic_mean(shapes, F, client=None, tolerance=1e-8, max_iterations=100,
                 shapes_per_task=None, initial=None, time_limit=None,
                 progress=False, **material):
    """The elastic mean argmin_s sum_i W[S_i, s] of `shapes` (N x #V x 3,
    one connectivity F), the minimiser shellspace.mean computes, with the
    per-shape terms (W, D_2 W, D_2^2 W at the current mean) computed as
    tasks in-process (client None) or on a dask.distributed Client, summed
    on the workers, and a safeguarded Newton step on the client each outer
    step (the scheme: the comment above this function in
    shellspace/collections.py). Converged when |G|_inf <= tolerance *
    max(1, |G(s_0)|_inf), s_0 the rigidly aligned vertex average (the
    library's start and target). shapes_per_task: default ceil(N / 64).
    initial: a starting mean. time_limit: seconds, then the current mean is
    returned unconverged (the clock only stops: the steps taken are the
    same digits). Material keywords as shellspace.mean (mu, lambda_, eta,
    relative_eta, bending; eta resolved from shapes[0]). Returns an
    ElasticMean; the same digits in-process and on any cluster."""
    shapes, F = _check_collection(shapes, F)
    n = len(shapes)
    _check_counts(max_iterations=max_iterations,
                  shapes_per_task=shapes_per_task,
                  optional=("shapes_per_task",))
    _check_real("tolerance", tolerance)
    material = _material(shapes, F, material)
    if shapes_per_task is None:
        shapes_per_task = max(1, math.ceil(n / 64))
    if int(shapes_per_task) < 1:
        raise shellspace.InputError("shapes_per_task must be >= 1")
    if isinstance(time_limit, tuple):  # ("deadline", t) of a verb's stages
        deadline = time_limit[1]
    else:
        deadline = _deadline(time_limit)
    if client is not None and not _await_workers(client, deadline):
        raise TimeLimitError("elastic mean: the time limit passed before "
                             "the scheduler had a worker")
    if initial is None:
        s = shapes[0].copy()
        for i in range(1, n):
            s += shellspace.align_rigidly(shapes[i], shapes[0])
        s /= n
    else:
        s, _ = _check_collection([initial], F)
        s = s[0]
        if s.shape != shapes[0].shape:
            raise shellspace.InputError(
                "initial: not the shapes' vertex count")
    terms = _Terms(shapes, F, client, int(shapes_per_task), material)
    current = terms(s)
    if current["infeasible"]:
        raise shellspace.InputError(
            f"elastic mean: the initial mean is degenerate "
            f"({current['infeasible']})")
    result = ElasticMean()
    result.initial_gradient_norm = float(np.abs(current["gradient"]).max())
    target = tolerance * max(1.0, result.initial_gradient_norm)
    history = []
    shift = 0.0
    termination = "max iterations"
    iterations = 0

    try:
        while True:
            G = current["gradient"]
            E = float(current["energies"].sum())
            gnorm = float(np.abs(G).max())
            if progress is True:
                print(f"\relastic mean: step {iterations} |G| {gnorm:.3e} "
                      f"(target {target:.1e})", end="", file=sys.stderr,
                      flush=True)
            elif callable(progress):
                progress(iterations, gnorm, target)
            if gnorm <= target:
                termination = "converged"
                break
            if iterations >= max_iterations:
                break
            if deadline is not None and time.monotonic() >= deadline:
                termination = "time limit"
                break
            iterations += 1
            rows, cols, vals = current["hessian"]
            unit = float(np.abs(vals[rows == cols]).mean())
            for _ in range(30):
                p, positive = shellspace.solve_modulo_rigid_motions(
                    rows, cols, vals, -G, s, shift=shift * unit)
                slope = float(np.dot(G.ravel(), p.ravel()))
                if positive and slope < 0:
                    break
                shift = max(1e-3, 10 * shift)
            else:
                termination = "no descent direction"
                break
            trial = s + p
            candidate = terms(trial)
            accepted = False
            if not candidate["infeasible"]:
                E_t = float(candidate["energies"].sum())
                accepted = (E_t <= E + 1e-4 * slope or
                            (np.linalg.norm(candidate["gradient"]) <
                             np.linalg.norm(G) and E_t <= E + 1e-10 * abs(E)))
            history.append((gnorm, E, shift, accepted))
            if accepted:
                s, current = trial, candidate
                shift = 0.0 if shift <= 1e-3 else shift / 10
            else:
                shift = max(1e-3, 10 * shift)
    except Stopped as stop:
        termination = f"stopped ({stop.signal_name})"
        stop.partial = result
        raise
    finally:
        if progress is True:
            print(file=sys.stderr)
        result.mean = shellspace.align_rigidly(s, shapes[0])
        result.energies = current["energies"]
        result.energy = float(current["energies"].sum())
        result.gradient_norm = float(np.abs(current["gradient"]).max())
        result.gradient_target = target
        result.converged = termination == "converged"
        result.termination = termination
        result.iterations = iterations
        result.rounds = terms.rounds
        result.history = history
        _read_only(result.mean, result.energies)
    return result


def log_task(shapes, F, i, mean, options):
    """v_i = LOG_K(mean -> A(S_i)), A the rigid alignment to the mean:
    (i, status, v or None, message, (wall, cpu) seconds)."""
    options = dict(options)
    blas_threads = options.pop("blas_threads", 1)
    clock = _Clock()
    try:
        with _BlasThreads(blas_threads):
            end = shellspace.align_rigidly(shapes[i], mean)
            v, _ = shellspace.log(mean, end, F, **options)
        return (i, OK, v, "", clock.seconds())
    except Exception as error:
        return (i, _status_of(error), None, _one_line(error), clock.seconds())


def _step_drift(path, F, material):
    """max_k |W[s_{k-1}, s_k] - W[s_0, s_1]| / W[s_0, s_1] of a path."""
    w = [shellspace.energy(path[k - 1], path[k], F, **material)["total"]
         for k in range(1, len(path))]
    return max(abs(x - w[0]) for x in w) / w[0] if w[0] > 0 else 0.0


def shoot_task(shapes, F, name, mean, variation, options):
    """EXP_K(mean, variation) with the library's safeguard (K = exp_steps,
    doubled up to max_exp_steps while a step has no solution or the step
    energies drift by more than half of the first), aligned to the mean:
    (name, status, shape or None, message)."""
    options = dict(options)
    blas_threads = options.pop("blas_threads", 1)
    steps = options.pop("exp_steps")
    most = options.pop("max_exp_steps")
    material = {k: options[k] for k in _MATERIAL_KEYS if k in options}
    steps = min(steps, most)
    try:
        with _BlasThreads(blas_threads):
            if not np.any(variation):
                return (name, OK, mean.copy(), "")
            while True:
                last = 2 * steps > most
                try:
                    path, _ = shellspace.shoot(mean, mean + variation / steps,
                                               F, steps=steps, **options)
                    ok = _step_drift(path, F, material) <= 0.5
                except (shellspace.NotConvergedError,
                        shellspace.InputError):
                    if last:
                        raise
                    ok, path = False, None
                if ok or last:
                    return (name, OK, shellspace.align_rigidly(path[-1], mean),
                            "")
                steps *= 2
    except Exception as error:
        return (name, _status_of(error), None, _one_line(error))


# The tasks whose first extra argument is a dict of solve keywords
# (time_limit among them): _run caps their time_limit in-process.
_SOLVE_TASKS = (geodesic_task, transfer_task, log_task, shoot_task)


class ShellPca:
    """mean, displacements (N x #V x 3, v_i = LOG_K(mean -> S_i)), gram
    (Gamma_ij = g(v_i, v_j) / N), eigenvalues (all N, descending), modes
    (w_j with g(w_j, w_k) = delta_jk, for eigenvalues above 1e-10 of the
    largest), mode_shapes {'mode_1_minus': ..., 'mode_1_plus': ...} (EXP
    shots, when asked), status (per shape), messages {i or name: line},
    mean_result (the ElasticMean when computed here)."""


def pca(shapes, F, client=None, mean=None, modes=3, log_steps=2,
        exp_steps=4, max_exp_steps=16, amplitude=1.0, mode_shapes=True,
        tolerance=1e-8, max_iterations=200, threads=1, blas_threads=1,
        progress=False, shapes_per_task=None, time_limit=None, **material):
    """Shell PCA of `shapes` at their elastic mean, as shellspace.pca: the
    metric g(u, w) = 1/2 u^T D_2^2 W[mean, mean] w, the displacements v_i =
    LOG_K(mean -> S_i) (K = log_steps, S_i aligned rigidly to the mean)
    one task each, the Gram matrix, its eigenpairs and the modes on the
    client, and (mode_shapes) the shapes EXP_K(mean, +-amplitude
    sqrt(lambda_j) w_j) for the first `modes` modes, one task each. mean:
    given (#V x 3), or None: elastic_mean(shapes, F, client, ...). A
    failed LOG leaves its shape out of the Gram matrix (its status and
    message say why). time_limit: seconds for every stage (the mean, the
    LOGs, the shots); the LOGs and shots it leaves are PENDING (out.pending
    True) and the model is that of the finished LOGs. Returns a ShellPca;
    the same digits in-process and on any cluster."""
    shapes, F = _check_collection(shapes, F)
    n = len(shapes)
    deadline = _deadline(time_limit)
    if n < 2:
        raise shellspace.InputError(f"pca needs at least 2 shapes, got {n}")
    for name, value in (("modes", modes), ("log_steps", log_steps),
                        ("exp_steps", exp_steps),
                        ("max_exp_steps", max_exp_steps)):
        _check_count(name, value, 1)
    _check_counts(max_iterations=max_iterations, threads=threads,
                  blas_threads=blas_threads, shapes_per_task=shapes_per_task,
                  optional=("shapes_per_task",))
    _check_real("tolerance", tolerance)
    _check_real("amplitude", amplitude, positive=False)
    if modes > n - 1:
        raise shellspace.InputError(
            f"modes must be at most {n - 1} (inputs - 1), got {modes}")
    if max_exp_steps < exp_steps:
        raise shellspace.InputError("max_exp_steps must be at least exp_steps")
    material = _material(shapes, F, material)
    out = ShellPca()
    out.mean_result = None
    if mean is None:
        out.mean_result = elastic_mean(
            shapes, F, client=client, tolerance=tolerance,
            shapes_per_task=shapes_per_task, progress=progress,
            time_limit=("deadline", deadline), **material)
        if not out.mean_result.converged:
            raise shellspace.NotConvergedError(
                f"elastic mean: |G| {out.mean_result.gradient_norm:.3g} above "
                f"{out.mean_result.gradient_target:.3g} "
                f"({out.mean_result.termination})")
        mean = out.mean_result.mean
    else:
        mean, _ = _check_collection([mean], F)
        mean = mean[0]
        if mean.shape != shapes[0].shape:
            raise shellspace.InputError("mean: not the shapes' vertex count")
    out.mean = mean
    options = dict(material, steps=log_steps, tolerance=tolerance,
                   max_iterations=max_iterations, threads=threads,
                   quiet=True, blas_threads=blas_threads)
    found = {}
    counter = _Progress(progress, n, "log")

    def on_log(item):
        if item[0] == "lost":
            i = item[1][0]
            found[i] = (LOST, None, item[2])
        else:
            i, status, v, message, _ = item
            found[i] = (status, v, message)
        counter.step(found[i][0] != OK)

    left = _run(log_task, [(i, mean) for i in range(n)], shapes, F, client,
                on_log, ("deadline", deadline), (options,))
    out.pending = bool(left)
    for i, _ in left:
        found[i] = (PENDING, None, "not computed: the time limit came first")
    out.status = np.array([found[i][0] for i in range(n)], dtype=np.int8)
    out.messages = {i: found[i][2] for i in range(n) if found[i][2]}
    used = [i for i in range(n) if found[i][0] == OK]
    out.used = used
    V = np.stack([found[i][1] for i in used]) if used else np.zeros(
        (0,) + mean.shape)
    out.displacements = V
    rows, cols, vals = shellspace.energy_hessian(mean, mean, F, **material)
    flat = V.reshape(len(used), mean.size)  # (0, 3 #V) when none finished
    HV = np.stack([np.bincount(rows, weights=vals * f[cols],
                               minlength=flat.shape[1]) for f in flat]) \
        if used else flat
    m = len(used)
    out.gram = 0.5 * flat @ HV.T / max(m, 1)
    eigenvalues, vectors = np.linalg.eigh(out.gram)
    order = np.argsort(eigenvalues)[::-1]
    out.eigenvalues = eigenvalues[order]
    vectors = vectors[:, order]
    top = out.eigenvalues[0] if m else 0.0
    out.modes = []
    for j in range(m):
        if not out.eigenvalues[j] > 1e-10 * max(top, 0.0):
            break
        w = (vectors[:, j] @ flat) / math.sqrt(m * out.eigenvalues[j])
        out.modes.append(w.reshape(mean.shape))
    out.mode_shapes = {}
    if mode_shapes:
        shots = []
        for j in range(min(modes, len(out.modes))):
            for sign, label in ((-1.0, "minus"), (1.0, "plus")):
                variation = (sign * amplitude * math.sqrt(out.eigenvalues[j])
                             * out.modes[j])
                shots.append((f"mode_{j + 1}_{label}", mean, variation))
        shot_options = dict(material, tolerance=tolerance,
                            max_iterations=max_iterations, threads=threads,
                            quiet=True, blas_threads=blas_threads,
                            exp_steps=exp_steps, max_exp_steps=max_exp_steps)
        counter = _Progress(progress, len(shots), "mode shapes")

        def on_shot(item):
            if item[0] == "lost":
                name = item[1][0]
                out.messages[name] = item[2]
            else:
                name, status, shape, message = item
                if status == OK:
                    out.mode_shapes[name] = shape
                else:
                    out.messages[name] = message
            counter.step(name not in out.mode_shapes)

        left = _run(shoot_task, shots, shapes, F, client, on_shot,
                    ("deadline", deadline), (shot_options,))
        for name, _, _ in left:
            out.pending = True
            out.messages[name] = "not computed: the time limit came first"
        out.mode_shapes = {name: out.mode_shapes[name]
                           for name, _, _ in shots if name in out.mode_shapes}
    _read_only(out.mean, out.displacements, out.gram, out.eigenvalues,
               *out.modes, *out.mode_shapes.values())
    return out


# ---- the command line -----------------------------------------------------

# A local worker's memory: local:N is bounded by the cores and by the
# physical memory at this much per worker (the CLI's bound too).
LOCAL_WORKER_BYTES = 512 * 2 ** 20
# Seconds to wait for a scheduler to answer, and for workers to register.
CONNECT_TIMEOUT = 3
WORKERS_TIMEOUT = 60


def most_local_workers():
    """The most workers local:N starts on this machine: one per core (at
    least 2), and LOCAL_WORKER_BYTES of physical memory each."""
    cores = os.cpu_count() or 1
    most = max(2, cores)
    try:
        memory = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
        most = min(most, max(1, memory // LOCAL_WORKER_BYTES))
    except (ValueError, OSError, AttributeError):
        pass
    return int(most)


def _parse_scheduler(scheduler):
    """('none', None), ('local', N) or ('address', ADDRESS) of a --scheduler
    value; InputError (one line) for anything else."""
    if scheduler in (None, "", "none"):
        return "none", None
    if not isinstance(scheduler, str):
        raise shellspace.InputError(
            f"scheduler: expected a string, got {type(scheduler).__name__}")
    lower = scheduler.lower()
    if lower != scheduler and (lower in ("none", "local") or
                               lower.startswith(("local:", "none:"))):
        raise shellspace.InputError(
            f"--scheduler '{scheduler}': the keywords none, local and local:N "
            f"are lower-case (did you mean '{lower}'?); an address is "
            "HOST:PORT")
    if scheduler.startswith("none:"):
        raise shellspace.InputError(
            f"--scheduler '{scheduler}': none takes no count (none, local, "
            "local:N or a scheduler address HOST:PORT)")
    most = most_local_workers()
    if scheduler == "local":
        return "local", min(2, most)
    if scheduler.startswith("local:"):
        count = scheduler[6:]
        if not count.isdigit() or not count.isascii() or int(count) < 1:
            raise shellspace.InputError(
                f"--scheduler: local:N needs a worker count N in 1..{most}, "
                f"got '{scheduler}'")
        if int(count) > most:
            raise shellspace.InputError(
                f"--scheduler {scheduler}: this machine holds at most {most} "
                "local workers (one per core, 512 MiB each)")
        return "local", int(count)
    address = scheduler
    for scheme in ("tcp://", "tls://"):
        if address.startswith(scheme):
            address = address[len(scheme):]
    host, _, port = address.rpartition(":")
    if (not host or not port.isdigit() or not port.isascii()
            or not 1 <= int(port) <= 65535 or "://" in address
            or any(c in host for c in " \t\n,/")):
        raise shellspace.InputError(
            "--scheduler: expected none, local, local:N or a scheduler "
            f"address HOST:PORT (tcp://HOST:8786, PORT 1..65535), got "
            f"'{scheduler}'")
    return "address", scheduler


def _client_for(scheduler):
    """(client, cluster or None) for local[:N] or a scheduler address; None
    for 'none' (in-process). A local cluster is returned once its workers
    registered; a scheduler that does not answer within CONNECT_TIMEOUT
    seconds is one InputError."""
    kind, value = _parse_scheduler(scheduler)
    if kind == "none":
        return None, None
    try:
        from distributed import Client, LocalCluster
    except ImportError as error:
        raise shellspace.InputError(
            f"--scheduler {scheduler} needs Dask's distributed package "
            f"({_one_line(error)}); --scheduler none runs in this process"
        ) from None
    if kind == "local":
        cluster = LocalCluster(n_workers=value, threads_per_worker=1,
                               processes=True, dashboard_address=None)
        client = Client(cluster)
        try:
            client.wait_for_workers(value, timeout=WORKERS_TIMEOUT)
        except Exception as error:
            client.close()
            cluster.close()
            raise shellspace.InputError(
                f"--scheduler {scheduler}: its {value} workers did not start "
                f"within {WORKERS_TIMEOUT} s ({_one_line(error)})") from None
        return client, cluster
    # A plain TCP connection first: a refused address is an error at once
    # (Dask's own connect retries for its whole timeout).
    address = value.split("://", 1)[-1]
    host, _, port = address.rpartition(":")
    try:
        import socket
        socket.create_connection((host.strip("[]"), int(port)),
                                 timeout=CONNECT_TIMEOUT).close()
        return Client(value, timeout=CONNECT_TIMEOUT), None
    except Exception as error:  # OSError, TimeoutError, ValueError
        raise shellspace.InputError(
            f"--scheduler {scheduler}: no scheduler answered within "
            f"{CONNECT_TIMEOUT} s ({_one_line(error)})") from None


def _split_inputs(inputs):
    """The paths of a comma-separated list. An empty item (",,", ", ,", a
    leading or trailing comma) is an InputError naming its position, and so
    is an item that names no file and begins or ends with white space ("a,
    b.ply"), as the CLI's lists (io/output_paths.h)."""
    paths = inputs.split(",")
    for k, p in enumerate(paths):
        position = f"item {k + 1} of {len(paths)}"
        empty = f"--inputs '{inputs}' has an empty item: {position}"
        if not p:
            raise shellspace.InputError(empty + (
                " (a trailing comma)" if k + 1 == len(paths) else
                " (a leading comma)" if k == 0 else
                " (two commas in a row)"))
        if not p.strip(" \t"):
            raise shellspace.InputError(
                empty + " (only white space between commas)")
        if p != p.strip() and not os.path.exists(p):
            raise shellspace.InputError(
                f"--inputs '{inputs}': {position}, '{p}', begins or ends "
                "with white space and names no file (items are split at the "
                "commas only: no space after a comma)")
    return paths


def _read_collection(inputs):
    """(paths, shapes, F) of a comma-separated list of meshes with one
    connectivity."""
    paths = _split_inputs(inputs)
    if len(paths) < 2:
        raise shellspace.InputError("--inputs needs at least 2 meshes")
    meshes = [shellspace.read_mesh(p) for p in paths]
    F = meshes[0][1]
    for p, (V, faces) in zip(paths, meshes):
        if faces.shape != F.shape or not np.array_equal(faces, F):
            raise shellspace.InputError(
                f"{p}: another connectivity than {paths[0]}")
    return paths, np.stack([V for V, _ in meshes]), F


class _OneLineParser(argparse.ArgumentParser):
    """argparse with its errors in one line (exit 2), not the usage text."""

    def error(self, message):
        self.exit(2, f"{self.prog}: {message} (--help lists the flags)\n")


def _parser():
    parser = _OneLineParser(
        prog="python3 -m shellspace.collections",
        description="Solves over a collection of shapes with one "
                    "connectivity, in-process or on Dask.")
    verbs = parser.add_subparsers(dest="verb", required=True,
                                  parser_class=_OneLineParser)

    def common(sub, what):
        sub.add_argument("--inputs", required=True,
                         help="comma-separated meshes (one connectivity)")
        sub.add_argument("--output", required=True, help=what)
        sub.add_argument("--scheduler", default="none",
                         help="none (in-process), local[:N] (N worker "
                              "processes, default 2) or a scheduler address "
                              "tcp://HOST:8786")
        sub.add_argument("--tolerance", type=float, default=1e-8)
        sub.add_argument("--max_iterations", type=int, default=None)
        sub.add_argument("--time_limit", type=float, default=None)
        sub.add_argument("--quiet", action="store_true")
        sub.add_argument("--mu", type=float, default=1.0)
        sub.add_argument("--lambda", dest="lambda_", type=float, default=1.0)
        sub.add_argument("--eta", type=float, default=None,
                         help="absolute bending weight (default: "
                              "relative_eta x the first shape's area)")
        sub.add_argument("--relative_eta", type=float, default=None)
        sub.add_argument("--bending", default="discrete-shells")

    d = verbs.add_parser("distances", help="the geodesic distance matrix")
    common(d, "the result, .npz")
    d.add_argument("--steps", type=int, default=4)
    d.add_argument("--pair_time_limit", type=float, default=None)
    d.add_argument("--cache", default=None,
                   help="resumable .npz cache (default: OUTPUT.cache.npz)")
    m = verbs.add_parser("mean", help="the elastic mean")
    common(m, "the mean, a mesh (.ply, .obj, .off)")
    p = verbs.add_parser("pca", help="shell PCA at the elastic mean")
    common(p, "the model, .npz")
    p.add_argument("--modes", type=int, default=3)
    p.add_argument("--log_steps", type=int, default=2)
    p.add_argument("--exp_steps", type=int, default=4)
    p.add_argument("--max_exp_steps", type=int, default=16)
    p.add_argument("--amplitude", type=float, default=1.0)
    return parser


def _on_stop_signal(number, frame):
    raise Stopped(number)


def _quiet_dask():
    """Dask's own log lines off (a stop or a closed cluster prints none)."""
    import logging
    for name in ("distributed", "tornado", "asyncio"):
        logging.getLogger(name).setLevel(logging.CRITICAL)


def _check_paths(args):
    """The output-path policy of every front end (the library's,
    io/output_paths.h), before anything is read or solved."""
    if args.verb in ("distances", "pca") and \
            not args.output.endswith(".npz"):
        raise shellspace.InputError("--output must end in .npz")
    if args.verb == "mean" and not args.output.lower().endswith(
            (".ply", ".obj", ".off")):
        raise shellspace.InputError("--output must end in .ply, .obj or "
                                    ".off")
    outputs = [("--output", args.output)]
    if args.verb == "distances":
        args.cache = args.cache or args.output[:-4] + ".cache.npz"
        if not args.cache.endswith(".npz"):
            raise shellspace.InputError("--cache must end in .npz")
        outputs.append(("--cache", args.cache))
    shellspace._check_output_paths(
        [("--inputs", p) for p in _split_inputs(args.inputs)], outputs)


def _check_numbers(args):
    """The counts and reals of the flags, before anything is read."""
    positive = ["tolerance", "mu", "lambda_"]
    counts = ["max_iterations"] + {
        "distances": ["steps"],
        "pca": ["modes", "log_steps", "exp_steps", "max_exp_steps"]}.get(
            args.verb, [])
    for name in positive + ["eta", "relative_eta"]:
        value = getattr(args, name)
        if value is not None and not (math.isfinite(value) and (
                value > 0 if name in positive else value >= 0)):
            flag = "--" + name.rstrip("_")
            raise shellspace.InputError(
                f"{flag} must be a finite number "
                f"{'> 0' if name in positive else '>= 0'}, got {value}")
    if args.bending not in ("discrete-shells", "shape-operator"):
        raise shellspace.InputError(
            f"unknown bending model '{args.bending}' (discrete-shells or "
            "shape-operator)")
    for name in counts:
        value = getattr(args, name)
        if value is not None and value < 1:
            raise shellspace.InputError(
                f"--{name} must be at least 1, got {value}")


def main(argv=None):
    """The command line; SIGTERM and SIGINT write what is finished (the
    distance matrix with its pending pairs, the mean so far), print one
    line and exit 143 / 130."""
    args = _parser().parse_args(argv)
    previous = {number: signal.signal(number, _on_stop_signal)
                for number in (signal.SIGTERM, signal.SIGINT)}
    client = cluster = None
    try:
        try:
            for name in ("time_limit", "pair_time_limit"):
                _deadline(getattr(args, name, None), "--" + name)
            if args.eta is not None and args.relative_eta is not None:
                raise shellspace.InputError(
                    "--eta and --relative_eta: give one, not both")
            _check_numbers(args)
            _check_paths(args)
            _parse_scheduler(args.scheduler)
            args.material = {k: v for k, v in (
                ("mu", args.mu), ("lambda_", args.lambda_), ("eta", args.eta),
                ("relative_eta", args.relative_eta),
                ("bending", args.bending)) if v is not None}
            paths, shapes, F = _read_collection(args.inputs)
            args.deadline = _deadline(args.time_limit)
            client, cluster = _client_for(args.scheduler)
            if args.verb == "distances":
                return _main_distances(args, paths, shapes, F, client)
            if args.verb == "mean":
                return _main_mean(args, paths, shapes, F, client)
            return _main_pca(args, paths, shapes, F, client)
        finally:
            if client is not None or cluster is not None:
                _quiet_dask()
                for closing in (client, cluster):
                    try:
                        if closing is not None:
                            closing.close()
                    except (Exception, Stopped):
                        pass
    except Stopped as stop:
        wrote = _write_partial(args, stop.partial)
        print(f"shellspace.collections: stopped ({stop.signal_name}): "
              + (f"wrote what is finished to {args.output}, marked partial"
                 if wrote else "no output"), file=sys.stderr)
        return stop.exit_code
    except TimeLimitError as error:
        print(f"shellspace.collections: {_one_line(error)}; no output",
              file=sys.stderr)
        return 124
    except (shellspace.InputError, ValueError, OSError) as error:
        print(f"shellspace.collections: {error}", file=sys.stderr)
        return 1
    except shellspace.NotConvergedError as error:
        print(f"shellspace.collections: {_one_line(error)}", file=sys.stderr)
        return 4
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)


def _write_partial(args, partial):
    """The partial result of a stopped verb written as its output; False
    if there is none to write."""
    try:
        if isinstance(partial, DistanceMatrix):
            _write_npz_atomically(
                args.output,
                inputs=np.array(_split_inputs(args.inputs), dtype=str),
                partial=np.array(True), **partial.arrays())
            return True
        if isinstance(partial, ElasticMean) and hasattr(partial, "mean"):
            V, F = shellspace.read_mesh(_split_inputs(args.inputs)[0])
            shellspace.write_mesh(args.output, partial.mean, F)
            return True
    except (Exception, Stopped):
        return False
    return False


def _main_distances(args, paths, shapes, F, client):
    result = distance_matrix(
        shapes, F, client=client, steps=args.steps, cache=args.cache,
        progress=not args.quiet, time_limit=args.time_limit,
        pair_time_limit=args.pair_time_limit, tolerance=args.tolerance,
        max_iterations=args.max_iterations or 200, **args.material)
    _write_npz_atomically(args.output, inputs=np.array(paths, dtype=str),
                          **result.arrays())
    failed = result.failed_pairs()
    pending = [p for p in failed if result.status[p] == PENDING]
    code = 124 if pending else 4 if failed else 0
    if not args.quiet or code != 0:  # a failure or stop is said even so
        print(f"distances: {len(paths)} shapes, "
              f"{len(paths) * (len(paths) - 1) // 2} pairs, "
              f"{result.computed} computed, {len(failed) - len(pending)} "
              f"failed, {len(pending)} pending -> {args.output}",
              file=sys.stderr)
    return code


def _main_mean(args, paths, shapes, F, client):
    result = elastic_mean(shapes, F, client=client, tolerance=args.tolerance,
                          max_iterations=args.max_iterations or 100,
                          time_limit=("deadline", args.deadline),
                          progress=not args.quiet, **args.material)
    shellspace.write_mesh(args.output, result.mean, F)
    code = (124 if result.termination == "time limit"
            else 0 if result.converged else 4)
    if not args.quiet or code != 0:  # a failure or stop is said even so
        print(f"mean: {len(paths)} shapes, {result.iterations} Newton steps "
              f"({result.rounds} rounds of tasks), |G| "
              f"{result.gradient_norm:.3g} (target "
              f"{result.gradient_target:.3g}), {result.termination} -> "
              f"{args.output}", file=sys.stderr)
    return code


def _main_pca(args, paths, shapes, F, client):
    if not 1 <= args.modes <= len(paths) - 1:
        raise shellspace.InputError(
            f"--modes must be in 1..{len(paths) - 1} (inputs - 1), got "
            f"{args.modes}")
    mean = elastic_mean(shapes, F, client=client, tolerance=args.tolerance,
                        time_limit=("deadline", args.deadline),
                        progress=not args.quiet, **args.material)
    if not mean.converged:
        print(f"shellspace.collections: elastic mean: |G| "
              f"{mean.gradient_norm:.3g} above {mean.gradient_target:.3g} "
              f"({mean.termination}); no output", file=sys.stderr)
        return 124 if mean.termination == "time limit" else 4
    # The time limit holds through every stage: the LOGs and the shots.
    remaining = (None if args.deadline is None
                 else max(1e-9, args.deadline - time.monotonic()))
    model = pca(shapes, F, client=client, mean=mean.mean, modes=args.modes,
                log_steps=args.log_steps, exp_steps=args.exp_steps,
                max_exp_steps=args.max_exp_steps, amplitude=args.amplitude,
                tolerance=args.tolerance,
                max_iterations=args.max_iterations or 200,
                progress=not args.quiet, time_limit=remaining,
                **args.material)
    names = sorted(model.mode_shapes)
    _write_npz_atomically(
        args.output, inputs=np.array(paths, dtype=str), faces=F,
        mean=model.mean, eigenvalues=model.eigenvalues,
        modes=np.array(model.modes), gram=model.gram, status=model.status,
        used=np.array(model.used, dtype=np.int64),
        displacements=model.displacements,
        mode_shape_names=np.array(names, dtype=str),
        mode_shapes=np.array([model.mode_shapes[k] for k in names]),
        message_keys=np.array([str(k) for k in model.messages], dtype=str),
        message_texts=np.array(list(model.messages.values()), dtype=str),
        partial=np.array(model.pending))
    failed = int(np.sum(model.status != OK)) + (
        2 * min(args.modes, len(model.modes)) - len(names))
    code = 124 if model.pending else 4 if failed else 0
    if not args.quiet or code != 0:  # a failure or stop is said even so
        values = ", ".join(f"{v:.4g}" for v in model.eigenvalues[:args.modes])
        print(f"pca: {len(paths)} shapes, {len(model.modes)} modes, "
              f"eigenvalues {values}, {failed} failed"
              f"{' (time limit: partial)' if model.pending else ''} -> "
              f"{args.output}", file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main())
