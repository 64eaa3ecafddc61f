// The peer's section-2 shadow-map frame (bench/peer_frame.hpp, the transcription of
// osmesa_bench's shadow_frameA), so that passim and the peer time the same work: 800x600,
// 12 bits (the peer draws 8), the paper's default ideal profile; the argument is the number of
// threads. bench/compare-with-peer runs it beside the peer.
#include <benchmark/benchmark.h>

#include "bench/peer_frame.hpp"
#include "pipeline/context.hpp"

using namespace passim;

namespace {

void BM_PeerShadowFrameA(benchmark::State& state) {
  FramebufferConfig c;
  c.width = 800;
  c.height = 600;
  c.color_bits = {12, 12, 12, 12};
  c.depth_bits = 24;
  c.stencil_bits = 0;
  c.accum_bits = 0;
  c.double_buffer = false;
  Context ctx(c);
  ctx.set_threads(static_cast<int>(state.range(0)));
  peer::ShadowFrame<Context> frame(ctx, 800, 600);
  frame.setup();
  for (auto _ : state) frame.frame();
  ctx.glFinish();
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_PeerShadowFrameA)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
