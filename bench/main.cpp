// Google Benchmark's main, with the allocator policy the passim program uses
// (pipeline/allocator.hpp), so that the figures are those of a passim run.
#include <benchmark/benchmark.h>

#include "pipeline/allocator.hpp"

int main(int argc, char** argv) {
  passim::keep_large_blocks_in_the_heap();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
