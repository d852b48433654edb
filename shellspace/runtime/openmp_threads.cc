#include "shellspace/runtime/openmp_threads.h"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>

namespace shellspace {

void SerialOpenMpInThisThread() {
  if (std::getenv("OMP_DYNAMIC") != nullptr ||
      std::getenv("OMP_THREAD_LIMIT") != nullptr) {
    return;
  }
  // OMP_NUM_THREADS=1 asks for what this does; any other value is the
  // user's choice of OpenMP threads, kept.
  const char* requested = std::getenv("OMP_NUM_THREADS");
  if (requested != nullptr && std::strcmp(requested, "1") != 0) return;
  using SetInt = void (*)(int);
  const auto set_dynamic =
      reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_dynamic"));
  const auto set_num_threads =
      reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"));
  const auto set_max_active_levels = reinterpret_cast<SetInt>(
      dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  if (set_dynamic == nullptr || set_num_threads == nullptr) return;
  set_num_threads(1);
  set_dynamic(1);
  if (set_max_active_levels != nullptr) set_max_active_levels(0);
}

}  // namespace shellspace
