// SerialOpenMpInThisThread (runtime/openmp_threads.h): the calling thread's
// OpenMP settings become one thread with dynamic adjustment, a thread that
// did not call it keeps the defaults, and ParallelFor's workers call it. The
// OpenMP runtime is the one CHOLMOD loads (the factorisation below pins
// the dependency and is checked against a closed form).
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <atomic>
#include <cstdlib>
#include <thread>
#include <vector>

#include "shellspace/runtime/openmp_threads.h"
#include "shellspace/runtime/parallel_for.h"
#include "shellspace/solvers/reusable_cholesky.h"

namespace shellspace {
namespace {

using GetInt = int (*)();

struct OpenMpSettings {
  int max_threads = -1;
  int dynamic = -1;
};

// This thread's nthreads-var and dyn-var, read through the runtime.
OpenMpSettings ThisThreadsSettings() {
  const auto max_threads =
      reinterpret_cast<GetInt>(dlsym(RTLD_DEFAULT, "omp_get_max_threads"));
  const auto dynamic =
      reinterpret_cast<GetInt>(dlsym(RTLD_DEFAULT, "omp_get_dynamic"));
  if (max_threads == nullptr || dynamic == nullptr) return {};
  return {max_threads(), dynamic()};
}

// Runs `read` on a new thread and returns what it saw.
OpenMpSettings OnAFreshThread(bool serialise) {
  OpenMpSettings seen;
  std::thread t([&]() {
    if (serialise) SerialOpenMpInThisThread();
    seen = ThisThreadsSettings();
  });
  t.join();
  return seen;
}

// Why the test cannot apply here, or "".
const char* NotApplicable() {
  if (std::getenv("OMP_NUM_THREADS") || std::getenv("OMP_DYNAMIC") ||
      std::getenv("OMP_THREAD_LIMIT")) {
    return "OMP_* set: the user's choice stands";
  }
  if (dlsym(RTLD_DEFAULT, "omp_get_dynamic") == nullptr) {
    return "no OpenMP runtime loaded (a CHOLMOD without OpenMP)";
  }
  return "";
}

// Solves diag(1, 2, ..., 40) x = 1 with CHOLMOD: x_i = 1 / (i + 1).
void FactoriseWithCholmod() {
  const int n = 40;
  Eigen::SparseMatrix<double> lower(n, n);
  for (int i = 0; i < n; ++i) lower.insert(i, i) = i + 1.0;
  std::vector<int> vertex_of(n);
  for (int i = 0; i < n; ++i) vertex_of[i] = i / 3;
  ReusableCholesky solver;
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.Solve(lower, vertex_of, (n + 2) / 3,
                           Eigen::VectorXd::Ones(n), 1e-12, &x));
  for (int i = 0; i < n; ++i) EXPECT_NEAR(x[i], 1.0 / (i + 1), 1e-15);
}

TEST(OpenMpThreadsTest, OneThreadWithDynamicAdjustmentInTheCallingThread) {
  FactoriseWithCholmod();
  if (*NotApplicable()) GTEST_SKIP() << NotApplicable();
  const OpenMpSettings serial = OnAFreshThread(true);
  EXPECT_EQ(serial.max_threads, 1);
  EXPECT_EQ(serial.dynamic, 1);
  // The twin: a thread that did not call it has dynamic adjustment off (so
  // CHOLMOD's num_threads(4) regions would get 4 threads).
  const OpenMpSettings plain = OnAFreshThread(false);
  EXPECT_EQ(plain.dynamic, 0);
}

// OMP_NUM_THREADS=1 asks for one thread, which nthreads-var alone does not
// give against CHOLMOD's num_threads(4): the dynamic adjustment is still
// set. Any other count is the user's and stands (the twin).
TEST(OpenMpThreadsTest, OmpNumThreadsOneStillSerialisesOthersStand) {
  FactoriseWithCholmod();
  if (*NotApplicable()) GTEST_SKIP() << NotApplicable();
  setenv("OMP_NUM_THREADS", "1", 1);
  const OpenMpSettings one = OnAFreshThread(true);
  setenv("OMP_NUM_THREADS", "2", 1);
  const OpenMpSettings two = OnAFreshThread(true);
  unsetenv("OMP_NUM_THREADS");
  EXPECT_EQ(one.dynamic, 1);
  EXPECT_EQ(one.max_threads, 1);
  EXPECT_EQ(two.dynamic, 0);
}

TEST(OpenMpThreadsTest, ParallelForWorkersAreSerialised) {
  FactoriseWithCholmod();
  if (*NotApplicable()) GTEST_SKIP() << NotApplicable();
  std::thread caller([]() {
    SerialOpenMpInThisThread();
    std::vector<OpenMpSettings> seen(8);
    ParallelFor(8, 3, [&](int i) { seen[i] = ThisThreadsSettings(); });
    for (int i = 0; i < 8; ++i) {
      EXPECT_EQ(seen[i].max_threads, 1) << i;
      EXPECT_EQ(seen[i].dynamic, 1) << i;
    }
  });
  caller.join();
}

}  // namespace
}  // namespace shellspace
