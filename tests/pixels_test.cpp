// Pixel rectangles (§3.6, §4.3) and the start of the imaging path, values by hand.
#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {
const GLubyte kImage[16] = {10, 0, 0, 255,  20, 0, 0, 255,   // row 0: groups (0,0), (1,0)
                            30, 0, 0, 255,  40, 0, 0, 255};  // row 1
}

TEST(Pixels, DrawPixelsAtTheRasterPositionWithZoom) {
  Context ctx(test::small_config(6, 6));
  test::window_projection(ctx);
  ctx.glRasterPos2i(1, 1);
  ctx.glDrawPixels(2, 2, GL_RGBA, GL_UNSIGNED_BYTE, kImage);
  EXPECT_EQ(pixel(ctx, 1, 1)[0], 10u);
  EXPECT_EQ(pixel(ctx, 2, 1)[0], 20u);
  EXPECT_EQ(pixel(ctx, 1, 2)[0], 30u);
  EXPECT_EQ(pixel(ctx, 2, 2)[0], 40u);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 0u);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 4u);
  // Zoom 2: group (i, j) covers [1 + 2i, 3 + 2i) x [1 + 2j, 3 + 2j).
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glPixelZoom(2, 2);
  ctx.glDrawPixels(2, 2, GL_RGBA, GL_UNSIGNED_BYTE, kImage);
  EXPECT_EQ(pixel(ctx, 1, 1)[0], 10u);
  EXPECT_EQ(pixel(ctx, 2, 2)[0], 10u);
  EXPECT_EQ(pixel(ctx, 3, 1)[0], 20u);
  EXPECT_EQ(pixel(ctx, 4, 4)[0], 40u);
  EXPECT_EQ(pixel(ctx, 5, 5)[0], 0u);
  // Zoom −1 in x: group i covers [1 − (i+1), 1 − i): group 0 -> pixel 0, group 1 -> pixel −1 (outside).
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glPixelZoom(-1, 1);
  ctx.glDrawPixels(2, 2, GL_RGBA, GL_UNSIGNED_BYTE, kImage);
  EXPECT_EQ(pixel(ctx, 0, 1)[0], 10u);
  EXPECT_EQ(pixel(ctx, 0, 2)[0], 30u);
  EXPECT_EQ(pixel(ctx, 1, 1)[0], 0u);
}

TEST(Pixels, RasterPositionIsRoundedA20AndCanBeInvalid) {
  Context ctx(test::small_config(4, 4));
  test::window_projection(ctx);
  ctx.glRasterPos2f(1.4f, 1.6f);  // -> (1, 2)
  ctx.glDrawPixels(1, 1, GL_RGBA, GL_UNSIGNED_BYTE, kImage);
  EXPECT_EQ(pixel(ctx, 1, 2)[0], 10u);
  ctx.glRasterPos2f(-5, 1);  // outside the clip volume: invalid, nothing is drawn
  ctx.glDrawPixels(1, 1, GL_RGBA, GL_UNSIGNED_BYTE, kImage + 4);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 1u);
}

TEST(Pixels, ReadPixelsWithScaleBiasAndLuminance) {
  Context ctx(test::small_config(2, 2));
  ctx.glClearColor(0.5f, 0.25f, 0.125f, 1);  // codes 128, 64, 32
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glPixelTransferf(GL_RED_SCALE, 2.0f);
  ctx.glPixelTransferf(GL_RED_BIAS, -0.25f);
  GLubyte rgba[4];
  ctx.glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  // 2·128/255 − 0.25 = 0.75392 -> 192.25 -> 192; G 64, B 32 unchanged.
  EXPECT_EQ(rgba[0], 192u);
  EXPECT_EQ(rgba[1], 64u);
  EXPECT_EQ(rgba[2], 32u);
  ctx.glPixelTransferf(GL_RED_SCALE, 1.0f);
  ctx.glPixelTransferf(GL_RED_BIAS, 0.0f);
  GLubyte lum = 0;
  ctx.glReadPixels(0, 0, 1, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE, &lum);
  EXPECT_EQ(lum, 224u);  // (128 + 64 + 32)/255 = 0.8784 -> 224
  GLfloat f[4];
  ctx.glPixelTransferf(GL_RED_SCALE, 4.0f);  // 2.0078: clamped to 1 even for FLOAT (A17)
  ctx.glReadPixels(0, 0, 1, 1, GL_RGBA, GL_FLOAT, f);
  EXPECT_EQ(f[0], 1.0f);
}

TEST(Pixels, CopyPixelsThroughTheColourMatrixSumsChannelsIntoAlpha) {
  // The colour-matrix half of the paper's Figure 4 (§3): a pixel (64, 64, 64, 63) copied
  // through a matrix whose alpha row sums the four channels gives alpha 255/255 -> 255;
  // (64, 0, 64, 0) gives 128.
  Context ctx(test::small_config(4, 1));
  test::window_projection(ctx);
  const GLubyte src[8] = {64, 64, 64, 63, 64, 0, 64, 0};
  ctx.glRasterPos2i(0, 0);
  ctx.glDrawPixels(2, 1, GL_RGBA, GL_UNSIGNED_BYTE, src);
  const double m[16] = {1, 0, 0, 1,  0, 1, 0, 1,  0, 0, 1, 1,  0, 0, 0, 1};  // column-major: A' = R+G+B+A
  ctx.glMatrixMode(GL_COLOR);
  ctx.glLoadMatrixd(m);
  ctx.glRasterPos2i(2, 0);
  ctx.glCopyPixels(0, 0, 2, 1, GL_COLOR);
  EXPECT_EQ(pixel(ctx, 2, 0)[3], 255u);
  EXPECT_EQ(pixel(ctx, 3, 0)[3], 128u);
  EXPECT_EQ(pixel(ctx, 2, 0)[0], 64u);
  EXPECT_EQ(ctx.total_counters().pixels_color_matrix, 2u);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(Pixels, Errors) {
  Context ctx(test::small_config(2, 2));
  ctx.glDrawPixels(-1, 1, GL_RGBA, GL_UNSIGNED_BYTE, kImage);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  ctx.glDrawPixels(1, 1, GL_RGBA, GL_BITMAP, kImage);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glCopyPixels(0, 0, 1, 1, GL_RGBA);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  GLubyte out[4];
  ctx.glReadPixels(0, 0, 1, 1, GL_COLOR_INDEX, GL_UNSIGNED_BYTE, out);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  FramebufferConfig cfg = test::small_config(2, 2);
  cfg.depth_bits = 0;
  Context nodepth(cfg);
  nodepth.glReadPixels(0, 0, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, out);
  EXPECT_EQ(nodepth.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  ctx.glPixelTransferf(GL_TEXTURE_2D, 1.0f);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}
