// The main of every benchmark: CHOLMOD's OpenMP regions on the calling
// thread alone, as in the CLI and the Python module
// (geometry/openmp_threads.h), so that the figures are what a user gets;
// then Google Benchmark.
#include <benchmark/benchmark.h>

#include "shellspace/geometry/openmp_threads.h"

int main(int argc, char** argv) {
  shellspace::SerialOpenMpInThisThread();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
