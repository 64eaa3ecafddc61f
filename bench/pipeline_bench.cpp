// Throughput of the spine (issue: flat fill, lit display-list scene), 800x600 at 12 bits,
// one core. Run: build/bench/passim_bench --benchmark_filter=...; figures in docs/performance.md.
#include <benchmark/benchmark.h>

#include "pipeline/context.hpp"
#include "programs/scenes.hpp"

using namespace passim;

namespace {

FramebufferConfig config_800x600(int bits) {
  FramebufferConfig c;
  c.width = 800;
  c.height = 600;
  c.color_bits = {bits, bits, bits, bits};
  c.depth_bits = 24;
  c.stencil_bits = 8;
  c.accum_bits = FramebufferConfig::default_accum_bits(c.color_bits);
  c.double_buffer = true;
  return c;
}

void full_quad(Context& ctx) {
  ctx.glBegin(GL_QUADS);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(800, 0);
  ctx.glVertex2f(800, 600);
  ctx.glVertex2f(0, 600);
  ctx.glEnd();
}

// a. Flat, depth-tested (LEQUAL, passing) full-screen quads: reads and writes depth and colour.
void BM_FillFlatDepth(benchmark::State& state) {
  Context ctx(config_800x600(static_cast<int>(state.range(0))));
  ctx.glMatrixMode(GL_PROJECTION);
  ctx.glOrtho(0, 800, 0, 600, -1, 1);
  ctx.glMatrixMode(GL_MODELVIEW);
  ctx.glShadeModel(GL_FLAT);
  ctx.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ctx.glEnable(GL_DEPTH_TEST);
  ctx.glDepthFunc(GL_LEQUAL);
  int i = 0;
  for (auto _ : state) {
    ctx.glColor4ub(static_cast<GLubyte>(i * 37), static_cast<GLubyte>(i * 91), static_cast<GLubyte>(i * 13), 255);
    full_quad(ctx);
    ++i;
  }
  state.SetItemsProcessed(state.iterations() * 800 * 600);
  state.counters["Mfrag/s"] = benchmark::Counter(static_cast<double>(state.iterations()) * 800 * 600 / 1e6,
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FillFlatDepth)->Arg(8)->Arg(12)->Unit(benchmark::kMillisecond);

// g. The 6944-triangle lit, smooth-shaded, depth-tested scene from a display list.
void BM_LitSceneDisplayList(benchmark::State& state) {
  Context ctx(config_800x600(static_cast<int>(state.range(0))));
  setup_bench_scene_view(ctx);
  ctx.glNewList(1, GL_COMPILE);
  const int triangles = emit_bench_scene(ctx);
  ctx.glEndList();
  for (auto _ : state) {
    ctx.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    ctx.glCallList(1);
  }
  state.counters["triangles"] = triangles;
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_LitSceneDisplayList)->Arg(8)->Arg(12)->Unit(benchmark::kMillisecond);

}  // namespace


