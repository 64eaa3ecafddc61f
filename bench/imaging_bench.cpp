// The pixel path, 800x600 RGBA at 12 bits, one core (imaging issue):
//  - glCopyPixels through a colour table and the colour matrix;
//  - a 3x3 RGBA convolution on a copy;
//  - glAccum(GL_ACCUM).
#include <benchmark/benchmark.h>

#include <vector>

#include "pipeline/context.hpp"

using namespace passim;

namespace {

FramebufferConfig config_12bit() {
  FramebufferConfig c;
  c.color_bits = {12, 12, 12, 12};
  c.accum_bits = 24;
  c.double_buffer = false;
  return c;
}

void setup(Context& ctx) {
  ctx.glMatrixMode(GL_PROJECTION);
  ctx.glOrtho(0, 800, 0, 600, -1, 1);
  ctx.glMatrixMode(GL_MODELVIEW);
  ctx.glClearColor(0.3f, 0.5f, 0.7f, 0.9f);
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glRasterPos2i(0, 0);
}

void rate(benchmark::State& state) {
  state.counters["Mpix/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 800 * 600 / 1e6, benchmark::Counter::kIsRate);
}

void BM_CopyPixelsColorTableMatrix(benchmark::State& state) {
  Context ctx(config_12bit());
  setup(ctx);
  std::vector<GLfloat> table(4096 * 4);
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = i >= 4 ? 0.25f : 0.0f;
  ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA, 4096, GL_RGBA, GL_FLOAT, table.data());
  ctx.glEnable(GL_COLOR_TABLE);
  const double m[16] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 0, 1};
  ctx.glMatrixMode(GL_COLOR);
  ctx.glLoadMatrixd(m);
  for (auto _ : state) ctx.glCopyPixels(0, 0, 800, 600, GL_COLOR);
  rate(state);
}
BENCHMARK(BM_CopyPixelsColorTableMatrix)->Unit(benchmark::kMillisecond);

void BM_CopyPixelsConvolution3x3(benchmark::State& state) {
  Context ctx(config_12bit());
  setup(ctx);
  const GLfloat filter[36] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0,
                              0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, filter);
  ctx.glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  ctx.glEnable(GL_CONVOLUTION_2D);
  for (auto _ : state) ctx.glCopyPixels(0, 0, 800, 600, GL_COLOR);
  rate(state);
}
BENCHMARK(BM_CopyPixelsConvolution3x3)->Unit(benchmark::kMillisecond);

void BM_AccumAccumulate(benchmark::State& state) {
  Context ctx(config_12bit());
  setup(ctx);
  for (auto _ : state) ctx.glAccum(GL_ACCUM, 0.25f);
  rate(state);
}
BENCHMARK(BM_AccumAccumulate)->Unit(benchmark::kMillisecond);

}  // namespace
