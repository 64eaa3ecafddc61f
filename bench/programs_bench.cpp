// Whole frames of the papers' programs (issue "programs", speed): the paper scene,
// 800x600, 512² map, 12 bits, shadow-map generation included, not recorded, images not
// read back (capturing and hashing them costs about 9 ms a frame); on one thread
// and on two (the argument; the same bits, tests/threads_test.cpp).
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
  o.threads = static_cast<int>(state.range(0));
  o.images = false;  // a frame as displayed: no read-back of its images
  ProgramSession session(o);
  for (auto _ : state) session.frame();
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK_CAPTURE(BM_ProgramFrame, shadow_map, "shadow-map", 0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ProgramFrame, pcf_2x2, "pcf", 2)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ProgramFrame, fast_pcf_2x2, "fast-pcf", 2)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_ProgramFrame, fast_pcf_4x4, "fast-pcf", 4)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
