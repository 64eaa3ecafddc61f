// The accumulation buffer (§4.2.4, A21) with values computed by hand.
#include <gtest/gtest.h>

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
