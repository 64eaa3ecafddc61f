// Texturing throughput, 800x600 at 12 bits, one core (texturing issue):
//  - a full-screen projective-textured (LINEAR) pass subtracted through the blend unit;
//  - a 1D-ramp texgen pass with a colour mask (the shadow-map depth encoding of §2).
#include <benchmark/benchmark.h>

#include <vector>

#include "pipeline/context.hpp"

using namespace passim;

namespace {

FramebufferConfig config_12bit() {
  FramebufferConfig c;
  c.color_bits = {12, 12, 12, 12};
  c.accum_bits = 24;
  return c;
}

void ortho_800x600(Context& ctx) {
  ctx.glMatrixMode(GL_PROJECTION);
  ctx.glOrtho(0, 800, 0, 600, -1, 1);
  ctx.glMatrixMode(GL_MODELVIEW);
}

void BM_ProjectiveTextureReverseSubtract(benchmark::State& state) {
  Context ctx(config_12bit());
  ortho_800x600(ctx);
  std::vector<GLubyte> img(512 * 512 * 4);
  for (std::size_t i = 0; i < img.size(); ++i) img[i] = static_cast<GLubyte>(i * 37);
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 512, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE, img.data());
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  ctx.glEnable(GL_TEXTURE_2D);
  ctx.glEnable(GL_BLEND);
  ctx.glBlendFunc(GL_ONE, GL_ONE);
  ctx.glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
  for (auto _ : state) {
    ctx.glBegin(GL_QUADS);  // q varies across the quad: a projective mapping
    ctx.glTexCoord4f(0, 0, 0, 1);
    ctx.glVertex2f(0, 0);
    ctx.glTexCoord4f(2, 0, 0, 2);
    ctx.glVertex2f(800, 0);
    ctx.glTexCoord4f(2, 2, 0, 2);
    ctx.glVertex2f(800, 600);
    ctx.glTexCoord4f(0, 1, 0, 1);
    ctx.glVertex2f(0, 600);
    ctx.glEnd();
  }
  state.counters["Mfrag/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 800 * 600 / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ProjectiveTextureReverseSubtract)->Unit(benchmark::kMillisecond);

void BM_RampTexgenColorMask(benchmark::State& state) {
  Context ctx(config_12bit());
  ortho_800x600(ctx);
  std::vector<GLushort> ramp(4096);
  for (int i = 0; i < 4096; ++i) ramp[static_cast<std::size_t>(i)] = static_cast<GLushort>(i * 16);
  ctx.glTexImage1D(GL_TEXTURE_1D, 0, GL_INTENSITY12, 4096, 0, GL_LUMINANCE, GL_UNSIGNED_SHORT, ramp.data());
  ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  ctx.glEnable(GL_TEXTURE_1D);
  const float plane[4] = {0.0f, 0.0f, -0.5f, 0.5f};  // s = (1 − z)/2
  ctx.glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
  ctx.glTexGenfv(GL_S, GL_EYE_PLANE, plane);
  ctx.glEnable(GL_TEXTURE_GEN_S);
  ctx.glColorMask(GL_TRUE, GL_FALSE, GL_FALSE, GL_FALSE);
  for (auto _ : state) {
    ctx.glBegin(GL_QUADS);
    ctx.glVertex3f(0, 0, -0.9f);
    ctx.glVertex3f(800, 0, 0.9f);
    ctx.glVertex3f(800, 600, 0.5f);
    ctx.glVertex3f(0, 600, -0.5f);
    ctx.glEnd();
  }
  state.counters["Mfrag/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 800 * 600 / 1e6, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RampTexgenColorMask)->Unit(benchmark::kMillisecond);

}  // namespace
