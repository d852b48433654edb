// The OpenMP parallel regions of SuiteSparse, serialised per thread.
// CHOLMOD 5 (Debian's SuiteSparse 5.12) opens OpenMP regions with a fixed
// num_threads(4) clause inside every supernodal factorisation, whatever
// OMP_NUM_THREADS says. On 2 cores those threads mostly wake each other:
// the LΘA reconstruction of two cactus frames (cactus 2, 10, 17 at 0, 2, 4,
// K = 4; 400 LM iterations) took 67.7 s wall / 55.2 s user + 67.6 s system
// time (4.4 million context switches) with them, 29.1 s / 29.5 + 2.0 s
// without (OMP_DYNAMIC=true OMP_NUM_THREADS=1). The heavy dense work of the
// factorisation is the BLAS's (blas_threads.h), not these regions.
#ifndef SHELLSPACE_RUNTIME_OPENMP_THREADS_H_
#define SHELLSPACE_RUNTIME_OPENMP_THREADS_H_

namespace shellspace {

// Makes the OpenMP parallel regions that the calling thread opens run on
// that thread alone: its nthreads-var becomes 1 and its dyn-var true, which
// caps even an explicit num_threads clause at 1 (OpenMP's dynamic
// adjustment, deterministic at nthreads-var 1), and its max-active-levels-var
// 0, so that no region is active and the runtime settles on one thread before
// the dynamic adjustment looks at the machine (libgomp's asks for the load
// average and the affinity mask at every region: 24,000 of each on the
// cactus 10-ring geodesic, K = 8). OpenMP keeps these settings
// per thread, so every thread that factorises calls it: the CLI's main,
// the Python module's import, ParallelFor's workers. Does nothing if the
// user set OMP_DYNAMIC, OMP_THREAD_LIMIT or OMP_NUM_THREADS to anything
// but 1 (OMP_NUM_THREADS=1 alone does not cap the clause: on the cactus
// 10-ring geodesic, K = 8, one thread, it cost 4.92 s CPU and 35,103
// context switches against 4.30 s and 112 with this), or if no
// OpenMP runtime is loaded (looked up at run time). The digits of a
// factorisation may differ from those with CHOLMOD's 4 threads; with the
// count fixed they repeat exactly.
void SerialOpenMpInThisThread();

}  // namespace shellspace

#endif  // SHELLSPACE_RUNTIME_OPENMP_THREADS_H_
