// The imaging subset's queries and copies (§3.6.3, §6.1.4): glGetColorTable,
// glGetConvolutionFilter, glGetSeparableFilter, glCopyColorSubTable, glCopyConvolutionFilter1D.
// Values by hand at 8 bits.
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "test_util.hpp"

using namespace passim;

namespace {

// A table is returned as stored: after COLOR_TABLE_SCALE/BIAS and the clamp, packed like
// ReadPixels (8-bit: round(v·255)); a LUMINANCE table returns L in R, G = B = 0, A = 1.
TEST(ImagingQueries, GetColorTableReturnsTheTableAsStored) {
  Context ctx(test::small_config(4, 4));
  const GLfloat scale[4] = {0.5f, 1.0f, 1.0f, 1.0f}, bias[4] = {0.0f, 0.0f, 0.25f, 0.0f};
  ctx.glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_SCALE, scale);
  ctx.glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_BIAS, bias);
  const GLubyte entries[8] = {200, 10, 20, 30, 8, 255, 200, 0};
  ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA8, 2, GL_RGBA, GL_UNSIGNED_BYTE, entries);
  GLubyte got[8] = {};
  ctx.glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_UNSIGNED_BYTE, got);
  // R: 200·0.5 = 100, 8·0.5 = 4; B: 20 + 0.25·255 = 83.75 -> 84, 200 + 63.75 -> 1 (clamped) -> 255.
  const GLubyte want[8] = {100, 10, 84, 30, 4, 255, 255, 0};
  for (int k = 0; k < 8; ++k) EXPECT_EQ(got[k], want[k]) << k;
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));

  const GLubyte lum[2] = {51, 204};
  ctx.glColorTable(GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_LUMINANCE8, 2, GL_LUMINANCE, GL_UNSIGNED_BYTE, lum);
  GLubyte rgba[8] = {};
  ctx.glGetColorTable(GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  const GLubyte want_lum[8] = {51, 0, 0, 255, 204, 0, 0, 255};
  for (int k = 0; k < 8; ++k) EXPECT_EQ(rgba[k], want_lum[k]) << k;

  ctx.glGetColorTable(GL_TEXTURE_2D, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glGetColorTable(GL_COLOR_TABLE, GL_DEPTH_COMPONENT, GL_UNSIGNED_BYTE, rgba);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}

// glCopyColorSubTable replaces entries start .. start + width − 1 from the framebuffer.
TEST(ImagingQueries, CopyColorSubTableFromTheFramebuffer) {
  Context ctx(test::small_config(4, 4));
  const GLubyte entries[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
  ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA8, 4, GL_RGBA, GL_UNSIGNED_BYTE, entries);
  ctx.glClearColor(51 / 255.0f, 102 / 255.0f, 153 / 255.0f, 204 / 255.0f);
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glCopyColorSubTable(GL_COLOR_TABLE, 1, 0, 0, 2);
  GLubyte got[16] = {};
  ctx.glGetColorTable(GL_COLOR_TABLE, GL_RGBA, GL_UNSIGNED_BYTE, got);
  const GLubyte want[16] = {1, 2, 3, 4, 51, 102, 153, 204, 51, 102, 153, 204, 13, 14, 15, 16};
  for (int k = 0; k < 16; ++k) EXPECT_EQ(got[k], want[k]) << k;
  ctx.glCopyColorSubTable(GL_COLOR_TABLE, 3, 0, 0, 2);  // past the table's 4 entries
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
}

// Filters are returned as stored (×FILTER_SCALE + FILTER_BIAS); a separable filter's row and
// column separately; glCopyConvolutionFilter1D takes the framebuffer's values.
TEST(ImagingQueries, GetConvolutionAndSeparableFilters) {
  Context ctx(test::small_config(4, 4));
  const GLfloat two[4] = {2, 2, 2, 2};
  ctx.glConvolutionParameterfv(GL_CONVOLUTION_2D, GL_CONVOLUTION_FILTER_SCALE, two);
  const GLfloat taps[6] = {0.25f, 0.125f, 0.0f, 0.5f, 0.375f, 0.0625f};  // 3x2 LUMINANCE
  ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_LUMINANCE, 3, 2, GL_LUMINANCE, GL_FLOAT, taps);
  GLfloat got[6] = {};
  ctx.glGetConvolutionFilter(GL_CONVOLUTION_2D, GL_RED, GL_FLOAT, got);
  const GLfloat want[6] = {0.5f, 0.25f, 0.0f, 1.0f, 0.75f, 0.125f};
  for (int k = 0; k < 6; ++k) EXPECT_FLOAT_EQ(got[k], want[k]) << k;

  const GLfloat row[2] = {0.25f, 0.5f}, column[3] = {0.125f, 0.375f, 0.0f};
  ctx.glSeparableFilter2D(GL_SEPARABLE_2D, GL_ALPHA, 2, 3, GL_ALPHA, GL_FLOAT, row, column);
  GLubyte r[8] = {}, c[12] = {};
  ctx.glGetSeparableFilter(GL_SEPARABLE_2D, GL_RGBA, GL_UNSIGNED_BYTE, r, c, nullptr);
  // ALPHA: R = G = B = 0; A = 0.25·255 = 63.75 -> 64, 0.5 -> 127.5 -> 128; 0.125 -> 31.875 -> 32, 0.375 -> 95.625 -> 96.
  const GLubyte want_r[8] = {0, 0, 0, 64, 0, 0, 0, 128}, want_c[12] = {0, 0, 0, 32, 0, 0, 0, 96, 0, 0, 0, 0};
  for (int k = 0; k < 8; ++k) EXPECT_EQ(r[k], want_r[k]) << k;
  for (int k = 0; k < 12; ++k) EXPECT_EQ(c[k], want_c[k]) << k;

  ctx.glClearColor(51 / 255.0f, 102 / 255.0f, 153 / 255.0f, 204 / 255.0f);
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glCopyConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, 0, 0, 3);
  GLubyte f1[12] = {};
  ctx.glGetConvolutionFilter(GL_CONVOLUTION_1D, GL_RGBA, GL_UNSIGNED_BYTE, f1);
  for (int t = 0; t < 3; ++t)
    for (int k = 0; k < 4; ++k) EXPECT_EQ(f1[4 * t + k], (51 * (k + 1))) << t << " " << k;
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ctx.glGetConvolutionFilter(GL_SEPARABLE_2D, GL_RGBA, GL_UNSIGNED_BYTE, f1);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}

}  // namespace
