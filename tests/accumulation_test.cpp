// The accumulation buffer (§4.2.4, A21) with values computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pipeline/fixed_point.hpp"
#include "pipeline/gl.hpp"
#include "stages/accumulate.hpp"
#include "stages/avx2.hpp"
#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {
void fill(Context& ctx, std::uint32_t code, int bits) {
  const float v = static_cast<float>(static_cast<double>(code) / ((1 << bits) - 1));
  ctx.glClearColor(v, v, v, 1);
  ctx.glClear(GL_COLOR_BUFFER_BIT);
}
}  // namespace

TEST(Accumulation, QuarterWeightedAccumulationReturnsTheRoundedMean) {
  // Codes 10, 20, 30, 41 at 8 bits: mean 25.25 -> 25; at 12 bits the same codes: 25.
  // Accumulation codes (A = 16 / 24): each step rounds to 1/(2^(A−1)−1), an error far below
  // half a colour step, so RETURN gives round(mean) exactly.
  // A second set, 8-bit codes 100, 101, 101, 101: mean 100.75 -> 101.
  for (int bits : {8, 12}) {
    const std::uint32_t sets[2][4] = {{10, 20, 30, 41}, {100, 101, 101, 101}};
    const std::uint32_t expected[2] = {25, 101};
    for (int s = 0; s < 2; ++s) {
      Context ctx(test::small_config(2, 2, bits));
      fill(ctx, sets[s][0], bits);
      ctx.glAccum(GL_LOAD, 0.25f);
      for (int k = 1; k < 4; ++k) {
        fill(ctx, sets[s][k], bits);
        ctx.glAccum(GL_ACCUM, 0.25f);
      }
      ctx.glAccum(GL_RETURN, 1.0f);
      EXPECT_EQ(pixel(ctx, 1, 1)[0], expected[s]) << "bits " << bits << " set " << s;
      EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
      const Counters t = ctx.total_counters();
      EXPECT_EQ(t.accum_load_pixels, 4u);
      EXPECT_EQ(t.accum_accum_pixels, 12u);
      EXPECT_EQ(t.accum_return_pixels, 4u);
    }
  }
}

TEST(Accumulation, MultAddClampAndColourMask) {
  Context ctx(test::small_config(1, 1, 8));
  fill(ctx, 153, 8);            // 0.6
  ctx.glAccum(GL_LOAD, 1.0f);   // acc = 0.6
  ctx.glAccum(GL_MULT, 0.5f);   // 0.3
  ctx.glAccum(GL_ADD, 0.25f);   // 0.55
  ctx.glClearColor(0, 0, 0, 0);
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glAccum(GL_RETURN, 1.0f);  // 0.55·255 = 140.25 -> 140
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 140u);
  ctx.glColorMask(GL_FALSE, GL_TRUE, GL_FALSE, GL_FALSE);
  ctx.glAccum(GL_RETURN, 2.0f);  // 1.1 clamps to 1 -> 255, green only
  const auto p = pixel(ctx, 0, 0);
  EXPECT_EQ(p[0], 140u);
  EXPECT_EQ(p[1], 255u);
  EXPECT_EQ(p[2], 140u);
  ctx.glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ctx.glAccum(GL_RETURN, -1.0f);  // negative clamps to 0
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 0u);
}

TEST(Accumulation, SaturatesInsteadOfWrapping) {
  // A21: results beyond [−1, 1] saturate: 0.75 + 0.75 -> 1, not a wrapped negative value.
  Context ctx(test::small_config(1, 1, 8));
  ctx.glAccum(GL_ADD, 0.75f);
  ctx.glAccum(GL_ADD, 0.75f);
  EXPECT_EQ(ctx.framebuffer().accum[0], 32767);
  ctx.glAccum(GL_ADD, -3.0f);
  EXPECT_EQ(ctx.framebuffer().accum[0], -32767);
}

TEST(Accumulation, Errors) {
  Context ctx(test::small_config(1, 1, 8));
  ctx.glAccum(GL_ONE, 1.0f);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  FramebufferConfig cfg = test::small_config(1, 1, 8);
  cfg.accum_bits = 0;
  Context none(cfg);
  none.glAccum(GL_ACCUM, 1.0f);
  EXPECT_EQ(none.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
}

TEST(Accumulation, ScissorLimitsTheRegion) {
  Context ctx(test::small_config(4, 1, 8));
  fill(ctx, 255, 8);
  ctx.glEnable(GL_SCISSOR_TEST);
  ctx.glScissor(1, 0, 2, 1);
  ctx.glAccum(GL_LOAD, 1.0f);
  EXPECT_EQ(ctx.framebuffer().accum[0], 0);
  EXPECT_EQ(ctx.framebuffer().accum[4], 32767);
  EXPECT_EQ(ctx.framebuffer().accum[12], 0);
  EXPECT_EQ(ctx.total_counters().accum_load_pixels, 2u);
}

TEST(Accumulation, ScissorBoxReachingPastIntMaxIsCutAtTheWindow) {
  // x + width = 1 + INT_MAX overflows an int: the box is computed in 64 bits, [1, 4) here.
  Context ctx(test::small_config(4, 1, 8));
  fill(ctx, 255, 8);
  ctx.glEnable(GL_SCISSOR_TEST);
  ctx.glScissor(1, 0, 2147483647, 1);
  ctx.glAccum(GL_LOAD, 1.0f);
  EXPECT_EQ(ctx.framebuffer().accum[0], 0);
  EXPECT_EQ(ctx.framebuffer().accum[4], 32767);
  EXPECT_EQ(ctx.framebuffer().accum[12], 32767);
  EXPECT_EQ(ctx.total_counters().accum_load_pixels, 3u);
  ctx.glClearColor(0, 0, 0, 0);
  ctx.glClear(GL_COLOR_BUFFER_BIT);  // the same box: pixel 0 keeps 255
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 255u);
  EXPECT_EQ(pixel(ctx, 3, 0)[0], 0u);
}

TEST(AccumulationKernels, Avx2RowsMatchTheScalarReferenceBitForBit) {
  // Random accumulation codes (the extremes included) and read codes, every operation, values
  // that saturate, NaN and infinities; the AVX2 rows must equal the scalar reference exactly.
  if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this processor";
  std::mt19937 rng(20261122);
  const double values[] = {0.25, -0.5, 1.0, 3.7, 1e-300, -0.0, 0.999999, std::nan(""), INFINITY, -INFINITY};
  const int n = 37;
  for (int abits : {8, 16, 24, 32})
    for (int cbits : {1, 5, 8, 12, 16})
      for (double value : values)
        for (GLenum op : {GL_ACCUM, GL_LOAD, GL_ADD, GL_MULT, GL_RETURN}) {
          AccumRowOp s;
          s.op = op;
          s.value = value;
          s.scale = static_cast<double>((std::int64_t{1} << (abits - 1)) - 1);
          const int bits[4] = {cbits, cbits, 8, 0};  // alpha absent: read as 1
          std::vector<double> terms[4];
          for (int k = 0; k < 4; ++k) {
            const std::uint32_t codes = bits[k] ? max_code(bits[k]) + 1 : 1;
            for (std::uint32_t c = 0; c < codes; ++c)
              terms[k].push_back(value * (bits[k] ? static_cast<double>(c) / max_code(bits[k]) : 1.0));
            s.term[k] = terms[k].data();
            s.code_mask[k] = bits[k] ? max_code(bits[k]) : 0;
            s.color_max[k] = static_cast<double>(max_code(bits[k]));
          }
          const auto limit = static_cast<std::int32_t>(s.scale);
          std::uniform_int_distribution<std::int32_t> acc_code(-limit, limit);
          std::vector<std::int32_t> acc(4 * n);
          std::vector<std::uint16_t> read(4 * n);
          for (int i = 0; i < 4 * n; ++i) {
            acc[static_cast<std::size_t>(i)] = i < 4 ? limit : i < 8 ? -limit : i < 12 ? 0 : acc_code(rng);
            const int k = i % 4;
            read[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(rng() & (bits[k] ? max_code(bits[k]) : 0));
          }
          if (op == GL_RETURN) {
            std::vector<std::uint16_t> scalar(4 * n), wide(4 * n);
            return_row_scalar(s, acc.data(), scalar.data(), n);
            return_row_avx2(s, acc.data(), wide.data(), n);
            EXPECT_EQ(scalar, wide) << "RETURN " << value << " accum " << abits << " colour " << cbits;
          } else {
            std::vector<std::int32_t> scalar = acc, wide = acc;
            accumulate_row_scalar(s, scalar.data(), read.data(), n);
            accumulate_row_avx2(s, wide.data(), read.data(), n);
            EXPECT_EQ(scalar, wide) << enum_name(op) << " " << value << " accum " << abits << " colour " << cbits;
          }
        }
}
