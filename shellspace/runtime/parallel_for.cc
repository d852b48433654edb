#include "shellspace/runtime/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "shellspace/runtime/openmp_threads.h"

namespace shellspace {

void ParallelFor(int count, int threads, const std::function<void(int)>& task) {
  std::atomic<int> next(0);
  std::atomic<bool> failed(false);
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&]() {
    for (int i = next++; i < count && !failed; i = next++) {
      try {
        task(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::min(threads, count); ++t) {
    pool.emplace_back([&worker]() {
      SerialOpenMpInThisThread();  // as the calling thread (the CLI, Python)
      worker();
    });
  }
  worker();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace shellspace
