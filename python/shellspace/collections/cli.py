"""The command line of shellspace.collections (`python3 -m
shellspace.collections distances|mean|pca`, and `shellspace collection
VERB`, which runs it): the flags, the scheduler, the inputs, the outputs
and the exit codes of the jobs."""
import argparse
import math
import os
import signal
import sys
import time

import numpy as np

import shellspace
from .distances import DistanceMatrix, distance_matrix
from .mean import ElasticMean, elastic_mean
from .pca import pca
from .scheduling import (OK, PENDING, CONNECT_TIMEOUT, WORKERS_TIMEOUT,
                         Stopped, TimeLimitError, deadline_of, one_line,
                         write_npz_atomically)

def most_local_workers():
    """The most workers local:N starts on this machine: one per core (at
    least 2), and 512 MiB of physical memory each (the CLI's bound)."""
    return shellspace._most_local_workers()


def _parse_scheduler(scheduler):
    """('none', None), ('local', N) or ('address', ADDRESS) of a --scheduler
    value (the library's ParseScheduler); InputError (one line) for
    anything else."""
    if scheduler in (None, ""):
        return "none", None
    if not isinstance(scheduler, str):
        raise shellspace.InputError(
            f"scheduler: expected a string, got {type(scheduler).__name__}")
    try:
        kind, value = shellspace._parse_scheduler(scheduler)
    except shellspace.InputError as error:
        raise shellspace.InputError(f"--scheduler: {error}") from None
    return kind, (min(2, most_local_workers()) if value == 0 else value)


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
            f"({one_line(error)}); --scheduler none runs in this process"
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
                f"within {WORKERS_TIMEOUT} s ({one_line(error)})") from None
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
            f"{CONNECT_TIMEOUT} s ({one_line(error)})") from None


def _read_collection(inputs):
    """(paths, shapes, F) of a comma-separated list of meshes with one
    connectivity (its items checked by _check_paths)."""
    paths = inputs.split(",")
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
    shellspace._check_output_paths([], outputs,
                                   input_lists=[("--inputs", args.inputs)])


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
                deadline_of(getattr(args, name, None), "--" + name)
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
            args.deadline = deadline_of(args.time_limit)
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
        print(f"shellspace.collections: {one_line(error)}; no output",
              file=sys.stderr)
        return 124
    except (shellspace.InputError, ValueError, OSError) as error:
        print(f"shellspace.collections: {error}", file=sys.stderr)
        return 1
    except shellspace.NotConvergedError as error:
        print(f"shellspace.collections: {one_line(error)}", file=sys.stderr)
        return 4
    finally:
        for number, handler in previous.items():
            signal.signal(number, handler)


def _write_partial(args, partial):
    """The partial result of a stopped verb written as its output; False
    if there is none to write."""
    try:
        if isinstance(partial, DistanceMatrix):
            write_npz_atomically(
                args.output,
                inputs=np.array(args.inputs.split(","), dtype=str),
                partial=np.array(True), **partial.arrays())
            return True
        if isinstance(partial, ElasticMean) and hasattr(partial, "mean"):
            V, F = shellspace.read_mesh(args.inputs.split(",")[0])
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
    write_npz_atomically(args.output, inputs=np.array(paths, dtype=str),
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
    write_npz_atomically(
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

