"""What every job of shellspace.collections shares: the status codes, the
checks of a collection and its keywords, the thread counts fixed per task,
and running tasks in this process or on Dask."""
import ctypes
import math
import os
import signal
import sys
import tempfile
import time

import numpy as np

import shellspace

# Status codes of a task's result (a distance's cell, a LOG's shape).
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
# Seconds to wait for a scheduler to answer, and for workers to register.
CONNECT_TIMEOUT = 3
WORKERS_TIMEOUT = 60


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


# ---- checks -----------------------------------------------------------------

def check_collection(shapes, F):
    """(shapes N x #V x 3 float64, F #F x 3 int64), or an InputError."""
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


def check_shape(name, shape, shapes, F):
    """One more shape of the collection (a mean, a detail), checked."""
    shape, _ = check_collection([shape], F)
    if shape[0].shape != shapes[0].shape:
        raise shellspace.InputError(f"{name}: not the shapes' vertex count")
    return shape[0]


def check_counts(minimum=1, optional=(), **values):
    """Count keywords: ints (not bools) >= minimum; those named in
    `optional` may be None."""
    for name, value in values.items():
        if value is None and name in optional:
            continue
        if isinstance(value, bool) or not isinstance(value,
                                                     (int, np.integer)):
            raise shellspace.InputError(f"{name} must be an integer, got "
                                        f"{type(value).__name__} {value!r}")
        if value < minimum:
            raise shellspace.InputError(
                f"{name} must be >= {minimum}, got {value}")


def check_real(name, value, positive=True):
    """A real keyword: a number (not a bool), finite, > 0 (positive) or
    >= 0."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(
            value, (int, float, np.integer, np.floating)):
        raise shellspace.InputError(f"{name} must be a real number, got "
                                    f"{type(value).__name__} {value!r}")
    if not math.isfinite(value) or not (value > 0 if positive
                                        else value >= 0):
        raise shellspace.InputError(
            f"{name} must be finite and {'> 0' if positive else '>= 0'}, "
            f"got {value}")


def deadline_of(time_limit, name="time_limit"):
    """The monotonic deadline of `time_limit` seconds (None or 0: none), or
    of a ("deadline", t) pair shared by the stages of a verb; a negative,
    NaN or non-number limit is an InputError."""
    if isinstance(time_limit, tuple):
        return time_limit[1]
    if time_limit is None:
        return None
    if isinstance(time_limit, bool) or not isinstance(
            time_limit, (int, float, np.integer, np.floating)):
        raise shellspace.InputError(f"{name} must be a number of seconds, "
                                    f"got {type(time_limit).__name__}")
    if not time_limit >= 0:
        raise shellspace.InputError(
            f"{name} must be >= 0 seconds (0 or None: no limit), got "
            f"{time_limit}")
    if time_limit == 0 or math.isinf(time_limit):
        return None
    return time.monotonic() + float(time_limit)


MATERIAL_KEYS = ("mu", "lambda_", "eta", "relative_eta", "bending")


def check_eta_pair(kwargs):
    """eta and relative_eta are one or the other (as the module's
    functions and the CLI's flags)."""
    if kwargs.get("eta") is not None and \
            kwargs.get("relative_eta") is not None:
        raise shellspace.InputError(
            "eta and relative_eta: give one of them (eta is absolute, "
            "relative_eta is multiplied by the first shape's area)")


def material_of(shapes, F, kwargs):
    """The material keywords with eta resolved once from shapes[0] (as
    shellspace.mean and shellspace.pca do): the per-shape functions would
    otherwise take it from their own first argument."""
    unknown = sorted(set(kwargs) - set(MATERIAL_KEYS))
    if unknown:
        raise shellspace.InputError(
            f"unknown keyword(s): {', '.join(unknown)}")
    material = dict(kwargs)
    check_eta_pair(material)
    if material.get("eta") is None:
        probe = shellspace.energy(shapes[0], shapes[0], F, **material)
        material["eta"] = float(probe["eta"])
    material.pop("relative_eta", None)
    return material


def read_only(*arrays):
    """The arrays of a result made read-only, as the module's results."""
    for array in arrays:
        if isinstance(array, np.ndarray):
            array.flags.writeable = False


# ---- one task ---------------------------------------------------------------

def _loaded_library(name):
    """The paths of the process's loaded libraries whose file name contains
    `name` (from /proc/self/maps)."""
    try:
        with open("/proc/self/maps") as maps:
            return sorted({line.split()[-1] for line in maps
                           if name in line.split()[-1]})
    except OSError:
        return []


class BlasThreads:
    """A task's thread counts fixed for a block: OpenBLAS's (restored
    after; the count changes the digits of the factorisations) and this
    thread's OpenMP regions serial (nthreads 1, dynamic), as the module
    does for its importing thread (runtime/openmp_threads.h): Dask's
    OMP_NUM_THREADS=1 leaves CHOLMOD's num_threads(4) regions at 4."""

    def __init__(self, threads):
        self.threads, self.lib, self.previous = threads, None, None
        for path in _loaded_library("libopenblas") if threads else []:
            try:
                lib = ctypes.CDLL(path)
                lib.openblas_get_num_threads.restype = ctypes.c_int
                lib.openblas_set_num_threads.argtypes = [ctypes.c_int]
                self.lib = lib
                break
            except (OSError, AttributeError):
                continue

    def __enter__(self):
        try:
            for path in _loaded_library("libgomp")[:1]:
                gomp = ctypes.CDLL(path)
                gomp.omp_set_num_threads(1)
                gomp.omp_set_dynamic(1)
        except (OSError, AttributeError):
            pass
        if self.lib is not None:
            self.previous = self.lib.openblas_get_num_threads()
            self.lib.openblas_set_num_threads(self.threads)
        return self

    def __exit__(self, *exc):
        if self.lib is not None and self.previous is not None:
            self.lib.openblas_set_num_threads(self.previous)
        return False


def status_of(error):
    """The status code of an exception a task caught."""
    if isinstance(error, shellspace.NotConvergedError):
        stop = getattr(error, "stop_reason", None)
        return (PAIR_TIME_LIMIT if str(stop or "").startswith("time limit")
                else NOT_CONVERGED)
    if isinstance(error, shellspace.InputError):
        return INPUT_ERROR
    return ERROR


def one_line(error):
    text = f"{type(error).__name__}: {error}"
    return text.splitlines()[0] if text else type(error).__name__


class Clock:
    """Wall and CPU seconds of a task: CPU of the calling thread (the task
    runs its solve in it)."""

    def __init__(self):
        self.wall, self.cpu = time.perf_counter(), time.thread_time()

    def seconds(self):
        return (time.perf_counter() - self.wall, time.thread_time() - self.cpu)


def solve_options(options):
    """(options without the task's own keys, blas_threads)."""
    options = dict(options)
    return options, options.pop("blas_threads", 1)


# ---- running tasks ----------------------------------------------------------

def await_workers(client, deadline):
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


class Progress:
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


def _in_process(function, items, shapes, F, on_result, deadline, options,
                extra):
    """The tasks one after the other; each solve stops at the deadline too
    (its own time_limit, if shorter, still holds), and one it stopped is
    not finished. Returns the items not finished."""
    for n, item in enumerate(items):
        if deadline is not None and time.monotonic() >= deadline:
            return items[n:]
        call_options = options
        if deadline is not None:
            call_options = dict(options)
            left = max(deadline - time.monotonic(), 1e-3)
            own = options.get("time_limit")
            call_options["time_limit"] = left if own in (None, 0) else min(
                own, left)
        value = function(shapes, F, *item, call_options, *extra)
        if deadline is not None and time.monotonic() >= deadline:
            return items[n:]
        on_result(value)
    return []


def run_tasks(function, items, shapes, F, client, on_result, time_limit,
              options, extra=()):
    """Calls function(shapes, F, *item, options, *extra) for every item,
    in-process (client None) or as one Dask task each with the shapes
    scattered once; on_result(result) on this thread as results arrive, or
    ("lost", item, message) for a task Dask gave up on. Returns the items
    not finished (the deadline passed). `time_limit`: seconds, or a
    ("deadline", monotonic time) pair shared by the stages of a verb."""
    deadline = deadline_of(time_limit)
    items = list(items)
    if client is None:
        return _in_process(function, items, shapes, F, on_result, deadline,
                           options, extra)
    from distributed import as_completed
    if not await_workers(client, deadline):
        return items
    shapes_future = client.scatter(shapes, broadcast=True, hash=False)
    faces_future = client.scatter(F, broadcast=True, hash=False)
    pending = {client.submit(function, shapes_future, faces_future, *item,
                             options, *extra, pure=False): item
               for item in items}
    results = as_completed(list(pending))
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
                    result = ("lost", item, one_line(error))
                on_result(result)
    finally:
        client.cancel(list(pending))
    return list(pending.values())


# ---- files ------------------------------------------------------------------

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


def write_npz_atomically(path, **arrays):
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
