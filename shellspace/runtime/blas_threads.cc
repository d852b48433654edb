#include "shellspace/runtime/blas_threads.h"

#include <dlfcn.h>

#include <cstdlib>

namespace shellspace {
namespace {

using SetThreads = void (*)(int);
using GetThreads = int (*)();

// OpenBLAS's functions if it is loaded (looked up at run time, so the
// library links against any BLAS).
SetThreads Setter() {
  return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
}
GetThreads Getter() {
  return reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
}

}  // namespace

ScopedBlasThreads::ScopedBlasThreads(int threads) {
  if (std::getenv("OPENBLAS_NUM_THREADS") != nullptr) return;
  const SetThreads set = Setter();
  const GetThreads get = Getter();
  if (set == nullptr || get == nullptr) return;
  previous_ = get();
  if (previous_ == threads) {
    previous_ = 0;
    return;
  }
  set(threads);
}

ScopedBlasThreads::~ScopedBlasThreads() {
  if (previous_ > 0) Setter()(previous_);
}

}  // namespace shellspace
