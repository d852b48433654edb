// A minimal parallel loop for the assembly routines of problems/.
#ifndef SHELLSPACE_RUNTIME_PARALLEL_FOR_H_
#define SHELLSPACE_RUNTIME_PARALLEL_FOR_H_

#include <functional>

namespace shellspace {

// Runs task(0), ..., task(count - 1) on up to `threads` threads (the calling
// thread is one of them), each index exactly once, in no particular order.
// If tasks throw, the remaining indices are skipped and the first exception
// is rethrown on the calling thread after all threads have joined.
void ParallelFor(int count, int threads, const std::function<void(int)>& task);

}  // namespace shellspace

#endif  // SHELLSPACE_RUNTIME_PARALLEL_FOR_H_
