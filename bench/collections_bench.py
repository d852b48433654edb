#!/usr/bin/env python3
"""The distance matrix of cactus poses in-process and on a Dask LocalCluster,
the scheduler's overhead per task, and the projection to a large collection.

    PYTHONPATH=build/python python3 bench/collections_bench.py \\
        [--poses 20] [--steps 4] [--workers 2] [--tiny_tasks 2000] \\
        [--only serial|cluster] [--save S.npz] [--compare S.npz]

prints: the serial matrix time and the mean wall and CPU time of one pair
(inside its task), the cluster's time and whether its matrix equals the
serial one bit for bit, the overhead per task (tiny tasks through the same
cluster: wall per task, and the CPU seconds the scheduler, client and
workers spent per task), and T = P t / W + P o for --project_shapes shapes
on --project_workers workers (P pairs, t the time of one pair, o the
overhead per task, counted as if the scheduler handled tasks one at a
time). --only runs one half, so that each can be measured on its own
(/usr/bin/time -v); --save keeps the serial matrix, --compare reads it
(the bitwise comparison and the serial t of the projection); --time_limit
stops each matrix (the pairs done are measured). --mean_poses M measures
the elastic mean of M poses instead: shellspace.mean, elastic_mean
in-process and on the cluster.
"""
import argparse
import os
import resource
import sys
import time

import numpy as np

import shellspace
import shellspace.collections as sc


def noop(x):
    return x


def cpu_seconds():
    """user + sys of this process (all its threads)."""
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def report_matrix(name, wall, result, n):
    upper = np.triu_indices(n, 1)
    print(file=sys.stderr)  # after the counter's line
    per_pair = np.nanmean(result.seconds[upper])
    cpu_pair = np.nanmean(result.cpu_seconds[upper])
    done = int(np.sum(result.status[upper] != sc.PENDING))
    print(f"{name}: {wall:.1f} s, {done} pairs, per pair {per_pair:.2f} s "
          f"wall, "
          f"{cpu_pair:.2f} s CPU inside its task "
          f"(CPU total {np.nansum(result.cpu_seconds[upper]):.1f} s), "
          f"{done - int(np.sum(result.status[upper] == sc.OK))} failed",
          flush=True)
    return per_pair, cpu_pair


def bench_mean(shapes, F, args):
    """The elastic mean three ways: shellspace.mean (LM + Newton in C++,
    one thread), elastic_mean in-process and on --workers workers."""
    n = len(shapes)
    size = np.linalg.norm(shapes[0].max(axis=0) - shapes[0].min(axis=0))
    clock, cpu = time.perf_counter(), cpu_seconds()
    reference, summary = shellspace.mean(shapes, F, threads=1, quiet=True)
    print(f"mean of {n} poses, shellspace.mean: "
          f"{time.perf_counter() - clock:.1f} s, CPU "
          f"{cpu_seconds() - cpu:.1f} s, |G| "
          f"{summary['final_gradient_norm']:.3g}, E {summary['energy']:.9g}",
          flush=True)
    clock, cpu = time.perf_counter(), cpu_seconds()
    here = sc.elastic_mean(shapes, F)
    print(f"elastic_mean in-process: {time.perf_counter() - clock:.1f} s, "
          f"CPU {cpu_seconds() - cpu:.1f} s, {here.iterations} Newton steps, "
          f"{here.rounds} rounds, |G| {here.gradient_norm:.3g} "
          f"({here.termination}), E {here.energy:.9g}, max vertex distance "
          f"to shellspace.mean "
          f"{np.abs(here.mean - reference).max() / size:.2e} of the diameter",
          flush=True)
    from distributed import Client, LocalCluster
    cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                           processes=True, dashboard_address=None)
    client = Client(cluster)
    try:
        clock = time.perf_counter()
        there = sc.elastic_mean(shapes, F, client=client)
        print(f"elastic_mean on {args.workers} workers: "
              f"{time.perf_counter() - clock:.1f} s, the same digits as "
              f"in-process: {np.array_equal(here.mean, there.mean)}",
              flush=True)
    finally:
        client.close()
        cluster.close()
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.environ.get(
        "SHELLSPACE_DATA_DIR", "../shared/data"))
    parser.add_argument("--poses", type=int, default=20)
    parser.add_argument("--steps", type=int, default=4)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--tiny_tasks", type=int, default=2000)
    parser.add_argument("--project_shapes", type=int, default=1000)
    parser.add_argument("--project_workers", type=int, default=100)
    parser.add_argument("--only", choices=["serial", "cluster"])
    parser.add_argument("--time_limit", type=float, default=None,
                        help="seconds for each matrix (then the pairs done "
                             "are measured and compared)")
    parser.add_argument("--mean_poses", type=int, default=0,
                        help="instead of the matrix: the elastic mean of the "
                             "first M poses by shellspace.mean and by "
                             "shellspace.collections.elastic_mean (in-process "
                             "and on the cluster)")
    parser.add_argument("--save", help="write the serial matrix (.npz)")
    parser.add_argument("--compare", help="a serial matrix saved by --save")
    args = parser.parse_args()

    meshes = []
    for k in range(args.poses):
        path = os.path.join(args.data, "cactus", f"cactus{k}.ply")
        if not os.path.exists(path):
            break
        meshes.append(shellspace.read_mesh(path))
    shapes = np.stack([V for V, _ in meshes])
    F = meshes[0][1]
    n = len(shapes)
    pairs = n * (n - 1) // 2
    print(f"cactus: {n} poses, {shapes.shape[1]} vertices, {pairs} pairs, "
          f"K = {args.steps}", flush=True)

    if args.mean_poses:
        return bench_mean(shapes[:args.mean_poses], F, args)

    serial = None
    times = []
    if args.only != "cluster":
        start = time.perf_counter()
        serial = sc.distance_matrix(shapes, F, steps=args.steps,
                                    progress=True,
                                    time_limit=args.time_limit)
        t, cpu = report_matrix("serial", time.perf_counter() - start, serial,
                               n)
        times.append(("serial", t, cpu))
        if args.save:
            np.savez(args.save, **serial.arrays())
    elif args.compare:
        with np.load(args.compare) as data:
            serial = sc.DistanceMatrix(n)
            serial.distances[...] = data["distances"]
            serial.status[...] = data["status"]
            upper = np.triu_indices(n, 1)
            times.append(("serial", np.nanmean(data["seconds"][upper]),
                          np.nanmean(data["cpu_seconds"][upper])))
    if args.only == "serial":
        return 0

    from distributed import Client, LocalCluster
    cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                           processes=True, dashboard_address=None)
    client = Client(cluster)
    try:
        start = time.perf_counter()
        result = sc.distance_matrix(shapes, F, client=client,
                                    steps=args.steps, progress=True,
                                    time_limit=args.time_limit)
        t, cpu = report_matrix(f"{args.workers} workers",
                               time.perf_counter() - start, result, n)
        times.append(("cluster", t, cpu))
        if serial is not None:  # the pairs both computed
            both = ((result.status != sc.PENDING) &
                    (serial.status != sc.PENDING))
            np.fill_diagonal(both, False)
            same = (np.array_equal(result.distances[both],
                                   serial.distances[both], equal_nan=True)
                    and np.array_equal(result.status[both],
                                       serial.status[both]))
            print(f"equal to serial bit for bit on the {both.sum() // 2} "
                  f"pairs both computed: {same}", flush=True)

        # The overhead: tiny tasks (an identity) through the same cluster;
        # CPU of this process (client and scheduler) and of the workers.
        client.gather(client.map(noop, range(50), pure=False))  # warm up
        workers_before = client.run(cpu_seconds)
        here_before = cpu_seconds()
        start = time.perf_counter()
        futures = client.map(noop, range(args.tiny_tasks), pure=False)
        client.gather(futures)
        tiny = time.perf_counter() - start
        here = cpu_seconds() - here_before
        workers_after = client.run(cpu_seconds)
        workers = sum(workers_after[w] - workers_before[w]
                      for w in workers_after)
        overhead = tiny / args.tiny_tasks
        print(f"overhead: {args.tiny_tasks} tiny tasks in {tiny:.2f} s, "
              f"{overhead * 1e3:.2f} ms per task (throughput "
              f"{1 / overhead:.0f} tasks/s); CPU per task "
              f"{here / args.tiny_tasks * 1e3:.2f} ms client + scheduler, "
              f"{workers / args.tiny_tasks * 1e3:.2f} ms workers", flush=True)
    finally:
        client.close()
        cluster.close()

    P = args.project_shapes * (args.project_shapes - 1) // 2
    W = args.project_workers
    for name, t, cpu in times:
        for what, value in (("wall", t), ("CPU", cpu)):
            T = P * value / W + P * overhead
            print(f"projection ({name} t, {what} {value:.2f} s): "
                  f"{args.project_shapes} shapes = {P} pairs on {W} workers: "
                  f"T = P t / W + P o = {T:.0f} s = {T / 3600:.1f} h "
                  f"(t at K = {args.steps} on this machine)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
