#include "shellspace/runtime/openmp_threads.h"

#include <dlfcn.h>

#include <cstdlib>

namespace shellspace {

void SerialOpenMpInThisThread() {
  if (std::getenv("OMP_NUM_THREADS") != nullptr ||
      std::getenv("OMP_DYNAMIC") != nullptr ||
      std::getenv("OMP_THREAD_LIMIT") != nullptr) {
    return;
  }
  using SetInt = void (*)(int);
  const auto set_dynamic =
      reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_dynamic"));
  const auto set_num_threads =
      reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"));
  if (set_dynamic == nullptr || set_num_threads == nullptr) return;
  set_num_threads(1);
  set_dynamic(1);
}

}  // namespace shellspace
