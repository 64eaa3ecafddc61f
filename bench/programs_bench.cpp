// Whole frames of the papers' programs (issue "programs", speed): the paper scene,
// 800x600, 512² map, 12 bits, shadow-map generation included, not recorded.
// Run: build/bench/passim_bench --benchmark_filter=Program; figures in docs/performance.md.
#include <benchmark/benchmark.h>

#include "programs/programs.hpp"

using namespace passim;

namespace {

void BM_ProgramFrame(benchmark::State& state, const char* program, int filter) {
  ProgramOptions o;
  o.program = program;
  o.filter = filter;
  o.color_bits = 12;
  o.scene = "paper";
  ProgramSession session(o);
  for (auto _ : state) session.frame();
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_ProgramFrame, shadow_map, "shadow-map", 0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ProgramFrame, pcf_2x2, "pcf", 2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ProgramFrame, fast_pcf_2x2, "fast-pcf", 2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ProgramFrame, fast_pcf_4x4, "fast-pcf", 4)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
