"""shellspace.collections: many independent solves over a collection of shapes
with one connectivity, in this process or on a Dask cluster.

    import shellspace.collections as sc
    result = sc.distance_matrix(shapes, F, steps=4)            # in-process
    result = sc.distance_matrix(shapes, F, client=client)      # on Dask
    result.distances, result.status, result.messages
    mean = sc.elastic_mean(shapes, F, client=client).mean  # shellspace.mean's
    model = sc.pca(shapes, F, client=client, mean=mean, modes=3)

The geodesic distance of a pair is sqrt(E_K) of its discrete geodesic
(E_K = K sum_k W[s_{k-1}, s_k], the path energy `geodesic` reports). Every
task is a pure function of (shapes, F, its item, options): the shapes are
scattered to the workers once, each task fixes its thread counts, so the
digits are those of the serial run whichever worker computes it, and a
task Dask reruns after a worker died gives the same digits again. A task
that fails gets a status code (OK ... LOST) and its own message; the others
are unaffected. The numerics are the library's: the module's geodesic,
log, shoot and transport per task, its Newton finish of the elastic mean
(elastic_mean_newton) and its PCA modes (pca_modes); this package
schedules them. One module per job (distances, mean, pca), the shared
scheduling, and the command line (cli):

    python3 -m shellspace.collections distances|mean|pca
        --inputs a.ply,b.ply,... --output D.npz|M.ply|P.npz
        [--scheduler local[:N]|ADDRESS] [--time_limit S] [--quiet]
        distances: [--steps K] [--pair_time_limit S] [--cache C.npz]
        pca: [--modes m] [--log_steps K] [--exp_steps K] [--amplitude t]
"""
from .scheduling import (OK, PENDING, NOT_CONVERGED, PAIR_TIME_LIMIT,
                         INPUT_ERROR, ERROR, LOST, STATUS_NAMES, RETRIED,
                         CONNECT_TIMEOUT, WORKERS_TIMEOUT, Stopped,
                         TimeLimitError)
from .distances import (CACHE_VERSION, DistanceMatrix, distance_matrix,
                        geodesic_task, map_geodesics, transfer, transfer_task)
from .mean import ElasticMean, add_mean_terms, elastic_mean, mean_terms_task
from .pca import ShellPca, log_task, pca, shoot_task
from .cli import _client_for, _parse_scheduler, main, most_local_workers
