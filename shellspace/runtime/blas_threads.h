// The thread count of the optimised BLAS (OpenBLAS) behind CHOLMOD, set for
// a scope: its worker threads spin between small factorisations, where they
// only cost CPU. Measured on 2 idle cores:
// `energy --bending shape-operator-edge-angles` on the faces subdivided once
// (28k vertices; two edge-angle fits) took 15.2 s wall / 24.4 s CPU with 2
// BLAS threads and 15.1 s / 15.0 s with 1; the finger geodesic pays for
// them (16.0 s vs 19.8 s wall), so the calculus keeps the default; the
// spline and regression solves use 1 (problems/splines/spline.cc: faster
// in wall time too). Deterministic: the count is fixed, not chosen by timing.
#ifndef SHELLSPACE_RUNTIME_BLAS_THREADS_H_
#define SHELLSPACE_RUNTIME_BLAS_THREADS_H_

namespace shellspace {

// Sets OpenBLAS's thread count to `threads` for the lifetime of the object
// and restores it after, unless the user fixed it with OPENBLAS_NUM_THREADS
// (then nothing changes). Without OpenBLAS (the reference BLAS: no such
// functions at run time) it does nothing.
class ScopedBlasThreads {
 public:
  explicit ScopedBlasThreads(int threads);
  ~ScopedBlasThreads();
  ScopedBlasThreads(const ScopedBlasThreads&) = delete;
  ScopedBlasThreads& operator=(const ScopedBlasThreads&) = delete;

 private:
  int previous_ = 0;  // 0: nothing to restore
};

}  // namespace shellspace

#endif  // SHELLSPACE_RUNTIME_BLAS_THREADS_H_
