"""The elastic mean of a collection, s_bar = argmin_s E(s), E(s) = sum_i
W[S_i, s] (shellspace.mean's): the library's Newton finish
(shellspace.elastic_mean_newton) with the per-shape terms W[S_i, s],
D_2 W[S_i, s] and D_2^2 W[S_i, s] at each point it asks for computed as
tasks of `shapes_per_task` shapes and summed in a fixed binary tree (on
the workers: only the sum comes back)."""
import math
import sys
import time

import numpy as np

import shellspace
from .scheduling import (BlasThreads, Stopped, TimeLimitError, await_workers,
                         check_collection, check_counts, check_real,
                         check_shape, deadline_of, material_of, read_only)


def _add_hessians(a, b):
    """Two Hessians as triplets (rows, cols, vals), summed: their values
    added where the patterns agree (energy_hessian's, set by F), else the
    triplets concatenated (the module sums duplicates)."""
    if np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1]):
        return a[0], a[1], a[2] + b[2]
    return tuple(np.concatenate([x, y]) for x, y in zip(a, b))


def mean_terms_task(shapes, F, indices, s, material):
    """sum over i in indices of (W[S_i, s], D_2 W[S_i, s], D_2^2 W[S_i, s])
    as a dict: energies (one per shape, in order), gradient (#V x 3),
    hessian (triplets); None where s is degenerate."""
    energies, gradient, hessian = [], np.zeros_like(s), None
    with BlasThreads(1):
        try:
            for i in indices:
                energies.append(float(shellspace.energy(
                    shapes[i], s, F, **material)["total"]))
                gradient += shellspace.energy_gradient(shapes[i], s, F,
                                                       **material)
                term = shellspace.energy_hessian(shapes[i], s, F, **material)
                hessian = term if hessian is None else _add_hessians(hessian,
                                                                     term)
        except shellspace.InputError:  # a degenerate trial
            return None
    return dict(energies=np.array(energies), gradient=gradient,
                hessian=hessian)


def add_mean_terms(a, b):
    """Two tasks' terms (of consecutive index ranges) summed: a + b."""
    if a is None or b is None:
        return None
    return dict(energies=np.concatenate([a["energies"], b["energies"]]),
                gradient=a["gradient"] + b["gradient"],
                hessian=_add_hessians(a["hessian"], b["hessian"]))


class _Terms:
    """The summed terms at s, in-process or on a client (the shapes
    scattered once); the same tasks and the same reduction tree either way,
    so the same digits. `last`: the last point and its terms."""

    def __init__(self, shapes, F, client, shapes_per_task, material):
        self.shapes, self.F, self.client = shapes, F, client
        n = len(shapes)
        self.chunks = [list(range(k, min(n, k + shapes_per_task)))
                       for k in range(0, n, shapes_per_task)]
        self.material = material
        self.rounds, self.last = 0, None
        if client is not None:
            self.shapes = client.scatter(shapes, broadcast=True, hash=False)
            self.F = client.scatter(F, broadcast=True, hash=False)

    def _tree(self, level, add):
        while len(level) > 1:
            level = [add(*level[k:k + 2]) if k + 1 < len(level) else level[k]
                     for k in range(0, len(level), 2)]
        return level[0]

    def __call__(self, s):
        """(E, G, H triplets) at s for elastic_mean_newton; None if s is
        degenerate."""
        self.rounds += 1
        if self.client is None:
            terms = self._tree([mean_terms_task(self.shapes, self.F, c, s,
                                                self.material)
                                for c in self.chunks], add_mean_terms)
        else:
            submit = self.client.submit
            s_future = self.client.scatter(s, broadcast=True, hash=False)
            terms = self._tree(
                [submit(mean_terms_task, self.shapes, self.F, c, s_future,
                        self.material, pure=False) for c in self.chunks],
                lambda a, b: submit(add_mean_terms, a, b, pure=False)
            ).result()
        self.last = (s, terms)
        if terms is None:
            return None
        return (float(terms["energies"].sum()), terms["gradient"],
                terms["hessian"])


class ElasticMean:
    """mean (#V x 3, aligned rigidly to shapes[0]), energy (sum_i W[S_i,
    mean]), energies (W[S_i, mean]), gradient_norm (|G|_inf at the mean),
    gradient_target, initial_gradient_norm, converged, termination,
    iterations (accepted Newton steps), rounds (evaluations of the terms:
    one set of tasks each), history [(|G|_inf, E, accepted)] after every
    line search."""


def elastic_mean(shapes, F, client=None, tolerance=1e-8, max_iterations=100,
                 shapes_per_task=None, initial=None, time_limit=None,
                 progress=False, **material):
    """The elastic mean argmin_s sum_i W[S_i, s] of `shapes` (N x #V x 3,
    one connectivity F), the minimiser shellspace.mean computes: the
    library's Newton finish (shellspace.elastic_mean_newton) from the
    aligned vertex average (or `initial`), its terms at each point computed
    as tasks in-process (client None) or on a dask.distributed Client.
    Converged when |G|_inf <= tolerance * max(1, |G(s_0)|_inf).
    shapes_per_task: default ceil(N / 64). time_limit: seconds, then the
    current mean is returned unconverged (the clock only stops: the steps
    taken are the same digits). Material keywords as shellspace.mean (mu,
    lambda_, eta, relative_eta, bending; eta resolved from shapes[0]).
    Returns an ElasticMean; the same digits in-process and on any
    cluster."""
    shapes, F = check_collection(shapes, F)
    check_counts(max_iterations=max_iterations,
                 shapes_per_task=shapes_per_task,
                 optional=("shapes_per_task",))
    check_real("tolerance", tolerance)
    material = material_of(shapes, F, material)
    shapes_per_task = shapes_per_task or max(1, math.ceil(len(shapes) / 64))
    deadline = deadline_of(time_limit)
    if client is not None and not await_workers(client, deadline):
        raise TimeLimitError("elastic mean: the time limit passed before "
                             "the scheduler had a worker")
    s = (shellspace.aligned_vertex_average(shapes) if initial is None
         else check_shape("initial", initial, shapes, F))
    terms = _Terms(shapes, F, client, int(shapes_per_task), material)
    result = ElasticMean()
    # The terms at the current point (the start, then each accepted trial)
    # and the target of the progress line.
    result.history, current, target = [], [None], [math.nan]

    def evaluate(s):
        value = terms(s)
        if current[0] is None:
            current[0] = terms.last
            if value is not None:
                target[0] = tolerance * max(1.0, np.abs(value[1]).max())
        return value

    def on_step(gradient_norm, energy, accepted):
        result.history.append((gradient_norm, energy, accepted))
        if accepted:
            current[0] = terms.last
        steps = sum(h[2] for h in result.history)
        if progress is True:
            print(f"\relastic mean: step {steps} |G| {gradient_norm:.3e} "
                  f"(target {target[0]:.1e})", end="", file=sys.stderr,
                  flush=True)
        elif callable(progress):
            progress(steps, gradient_norm, target[0])

    def finish(s, report):
        result.mean = shellspace.align_rigidly(s, shapes[0])
        result.energies = current[0][1]["energies"]
        result.energy = float(result.energies.sum())
        result.rounds = terms.rounds
        for key, value in report.items():
            if key != "mean":
                setattr(result, key, value)
        read_only(result.mean, result.energies)
        return result

    try:
        report = shellspace.elastic_mean_newton(
            s, F, evaluate, tolerance=tolerance,
            max_iterations=max_iterations, on_step=on_step,
            stop=lambda: deadline is not None and time.monotonic() >= deadline)
    except Stopped as stop:
        if current[0] is not None and current[0][1] is not None:
            stop.partial = finish(current[0][0], dict(
                termination=f"stopped ({stop.signal_name})", converged=False))
        raise
    finally:
        if progress is True:
            print(file=sys.stderr)
    if report["stopped"]:
        report["termination"] = "time limit"
    return finish(report["mean"], report)
