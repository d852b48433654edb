#!/usr/bin/env python3
"""The distance matrix of cactus poses in-process and on a Dask LocalCluster,
the scheduler's overhead per task, and the projection to a large collection.

    PYTHONPATH=build/python python3 bench/collections_bench.py \
        [--poses 20] [--steps 4] [--workers 2] [--tiny_tasks 2000]

prints: the serial matrix time and the mean time of one pair (its task's
wall time), the cluster's time and whether its matrix equals the serial one
bit for bit, the overhead per task (tiny tasks through the same cluster),
and T = P t / W + P o for --project_shapes shapes on --project_workers
workers (P pairs, t the measured time of one pair, o the overhead per task,
counted as if the scheduler handled tasks one at a time).
"""
import argparse
import os
import sys
import time

import numpy as np

import shellspace
import shellspace.collections as sc


def noop(x):
    return x


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
    parser.add_argument("--skip_serial", action="store_true")
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

    serial = None
    if not args.skip_serial:
        start = time.perf_counter()
        serial = sc.distance_matrix(shapes, F, steps=args.steps,
                                    progress=True)
        wall = time.perf_counter() - start
        per_pair = np.nanmean(serial.seconds[np.triu_indices(n, 1)])
        print(f"serial: {wall:.1f} s, {per_pair:.2f} s per pair, "
              f"{len(serial.failed_pairs())} failed", flush=True)

    from distributed import Client, LocalCluster
    cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1,
                           processes=True, dashboard_address=None)
    client = Client(cluster)
    try:
        start = time.perf_counter()
        result = sc.distance_matrix(shapes, F, client=client,
                                    steps=args.steps, progress=True)
        wall = time.perf_counter() - start
        per_pair = np.nanmean(result.seconds[np.triu_indices(n, 1)])
        same = (serial is not None and
                np.array_equal(result.distances, serial.distances,
                               equal_nan=True) and
                np.array_equal(result.status, serial.status))
        print(f"{args.workers} workers: {wall:.1f} s, {per_pair:.2f} s per "
              f"pair inside its task, equal to serial bit for bit: "
              f"{same if serial is not None else 'not compared'}", flush=True)

        # The overhead: tiny tasks (an identity) through the same cluster.
        client.gather(client.map(noop, range(50), pure=False))  # warm up
        start = time.perf_counter()
        futures = client.map(noop, range(args.tiny_tasks), pure=False)
        client.gather(futures)
        tiny = time.perf_counter() - start
        overhead = tiny / args.tiny_tasks
        print(f"overhead: {args.tiny_tasks} tiny tasks in {tiny:.2f} s, "
              f"{overhead * 1e3:.2f} ms per task (scheduler throughput "
              f"{1 / overhead:.0f} tasks/s)", flush=True)
    finally:
        client.close()
        cluster.close()

    P = args.project_shapes * (args.project_shapes - 1) // 2
    W = args.project_workers
    times = [("cluster", per_pair)]
    if serial is not None:  # one pair on one otherwise idle core
        times.insert(0, ("serial", np.nanmean(
            serial.seconds[np.triu_indices(n, 1)])))
    for name, t in times:
        T = P * t / W + P * overhead
        print(f"projection ({name} t): {args.project_shapes} shapes = {P} "
              f"pairs on {W} workers: T = P t / W + P o = {P} x {t:.2f} s / "
              f"{W} + {P} x {overhead * 1e3:.2f} ms = {T:.0f} s = "
              f"{T / 3600:.1f} h (t at K = {args.steps} on this machine)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
