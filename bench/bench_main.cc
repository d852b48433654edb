// The main of every benchmark: CHOLMOD's OpenMP regions on the calling
// thread alone, as in the CLI and the Python module
// (runtime/openmp_threads.h), and the heap kept for reuse as the CLI keeps
// it (runtime/heap_reuse.h), so that the figures are what a user gets;
// then Google Benchmark.
#include <benchmark/benchmark.h>

#include "shellspace/runtime/heap_reuse.h"
#include "shellspace/runtime/openmp_threads.h"

int main(int argc, char** argv) {
  shellspace::SerialOpenMpInThisThread();
  shellspace::KeepFreedHeapForReuse();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
