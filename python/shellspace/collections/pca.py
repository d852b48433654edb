"""Shell PCA of a collection at its elastic mean (shellspace.pca's model):
the LOGs v_i = LOG_K(mean -> S_i) one task each, the Gram matrix, its
eigenpairs and the modes by the library (shellspace.pca_modes), and the
mode shapes EXP_K(mean, +-amplitude sqrt(lambda_j) w_j) one task each
(shellspace.shoot_from_mean)."""
import math

import numpy as np

import shellspace
from .mean import elastic_mean
from .scheduling import (OK, PENDING, LOST, BlasThreads, Clock,
                         Progress, check_collection, check_counts, check_real,
                         check_shape, deadline_of, material_of, one_line,
                         read_only, run_tasks, solve_options, status_of)


def log_task(shapes, F, i, mean, options):
    """v_i = LOG_K(mean -> A(S_i)), A the rigid alignment to the mean:
    (i, status, v or None, message, (wall, cpu) seconds)."""
    options, blas_threads = solve_options(options)
    clock = Clock()
    try:
        with BlasThreads(blas_threads):
            end = shellspace.align_rigidly(shapes[i], mean)
            v, _ = shellspace.log(mean, end, F, **options)
        return (i, OK, v, "", clock.seconds())
    except Exception as error:
        return (i, status_of(error), None, one_line(error), clock.seconds())


def shoot_task(shapes, F, name, mean, variation, options):
    """A mode shape: shellspace.shoot_from_mean (EXP_K with the library's
    safeguard, aligned to the mean): (name, status, shape or None,
    message)."""
    options, blas_threads = solve_options(options)
    try:
        with BlasThreads(blas_threads):
            shape = shellspace.shoot_from_mean(mean, variation, F, **options)
        return (name, OK, shape, "")
    except Exception as error:
        return (name, status_of(error), None, one_line(error))


class ShellPca:
    """mean, displacements (v_i = LOG_K(mean -> S_i) of the shapes in
    `used`), gram (Gamma_ij = g(v_i, v_j) / n), eigenvalues (all n,
    descending), modes (w_j with g(w_j, w_k) = delta_jk, for eigenvalues
    above 1e-10 of the largest; each signed so that its largest
    coefficient in the v_i is positive), mode_shapes {'mode_1_minus': ...,
    'mode_1_plus': ...} (EXP shots, when asked), status (per shape),
    messages {i or name: line}, pending (the time limit left some),
    mean_result (the ElasticMean when computed here)."""


def _modes(out, mean, F, material):
    """The Gram matrix, eigenvalues and modes of out.displacements."""
    if len(out.used):
        out.gram, out.eigenvalues, modes = shellspace.pca_modes(
            mean, out.displacements, F, **material)
        out.modes = list(modes)
    else:
        out.gram, out.eigenvalues, out.modes = np.zeros((0, 0)), np.zeros(0), []


def _mode_shapes(out, shapes, F, client, modes, amplitude, options,
                 progress, deadline):
    """EXP shots of the first `modes` modes at +-amplitude into out."""
    shots = [(f"mode_{j + 1}_{label}", out.mean,
              sign * amplitude * math.sqrt(out.eigenvalues[j]) * out.modes[j])
             for j in range(min(modes, len(out.modes)))
             for sign, label in ((-1.0, "minus"), (1.0, "plus"))]
    counter = Progress(progress, len(shots), "mode shapes")
    found = {}

    def on_shot(item):
        name, status, shape, message = (
            (item[1][0], LOST, None, item[2]) if item[0] == "lost" else item)
        if status == OK:
            found[name] = shape
        else:
            out.messages[name] = message
        counter.step(status != OK)

    left = run_tasks(shoot_task, shots, shapes, F, client, on_shot,
                     ("deadline", deadline), options)
    for name, _, _ in left:
        out.pending = True
        out.messages[name] = "not computed: the time limit came first"
    out.mode_shapes = {name: found[name] for name, _, _ in shots
                       if name in found}


def pca(shapes, F, client=None, mean=None, modes=3, log_steps=2,
        exp_steps=4, max_exp_steps=16, amplitude=1.0, mode_shapes=True,
        tolerance=1e-8, max_iterations=200, threads=1, blas_threads=1,
        progress=False, shapes_per_task=None, time_limit=None, **material):
    """Shell PCA of `shapes` at their elastic mean, as shellspace.pca: the
    displacements v_i = LOG_K(mean -> S_i) (K = log_steps, S_i aligned
    rigidly to the mean) one task each, then shellspace.pca_modes (the
    metric g(u, w) = 1/2 u^T D_2^2 W[mean, mean] w, the Gram matrix, its
    eigenpairs and the modes) on the client, and (mode_shapes) the shapes
    EXP_K(mean, +-amplitude sqrt(lambda_j) w_j) for the first `modes` modes,
    one task each. mean: given (#V x 3), or None: elastic_mean(shapes, F,
    client, ...). A failed LOG leaves its shape out of the Gram matrix (its
    status and message say why). time_limit: seconds for every stage (the
    mean, the LOGs, the shots); the LOGs and shots it leaves are PENDING
    (out.pending True) and the model is that of the finished LOGs. Returns
    a ShellPca; the same digits in-process and on any cluster."""
    shapes, F = check_collection(shapes, F)
    n = len(shapes)
    deadline = deadline_of(time_limit)
    if n < 2:
        raise shellspace.InputError(f"pca needs at least 2 shapes, got {n}")
    check_counts(modes=modes, log_steps=log_steps, exp_steps=exp_steps,
                 max_exp_steps=max_exp_steps, max_iterations=max_iterations,
                 threads=threads, blas_threads=blas_threads,
                 shapes_per_task=shapes_per_task,
                 optional=("shapes_per_task",))
    check_real("tolerance", tolerance)
    check_real("amplitude", amplitude, positive=False)
    if modes > n - 1:
        raise shellspace.InputError(
            f"modes must be at most {n - 1} (inputs - 1), got {modes}")
    if max_exp_steps < exp_steps:
        raise shellspace.InputError("max_exp_steps must be at least exp_steps")
    material = material_of(shapes, F, material)
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
    out.mean = mean = check_shape("mean", mean, shapes, F)
    options = dict(material, tolerance=tolerance,
                   max_iterations=max_iterations, threads=threads,
                   quiet=True, blas_threads=blas_threads)
    found = {}
    counter = Progress(progress, n, "log")

    def on_log(item):
        i, status, v, message = (
            (item[1][0], LOST, None, item[2]) if item[0] == "lost"
            else item[:4])
        found[i] = (status, v, message)
        counter.step(status != OK)

    left = run_tasks(log_task, [(i, mean) for i in range(n)], shapes, F,
                     client, on_log, ("deadline", deadline),
                     dict(options, steps=log_steps))
    out.pending = bool(left)
    for i, _ in left:
        found[i] = (PENDING, None, "not computed: the time limit came first")
    out.status = np.array([found[i][0] for i in range(n)], dtype=np.int8)
    out.messages = {i: found[i][2] for i in range(n) if found[i][2]}
    out.used = [i for i in range(n) if found[i][0] == OK]
    out.displacements = np.stack([found[i][1] for i in out.used]) \
        if out.used else np.zeros((0,) + mean.shape)
    _modes(out, mean, F, material)
    out.mode_shapes = {}
    if mode_shapes:
        _mode_shapes(out, shapes, F, client, modes, amplitude,
                     dict(options, exp_steps=exp_steps,
                          max_exp_steps=max_exp_steps),
                     progress, deadline)
    read_only(out.mean, out.displacements, out.gram, out.eigenvalues,
              *out.modes, *out.mode_shapes.values())
    return out
