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

// Found by fuzzing: a zoom of 4e9 put the group's pixel range past int. Group (0, 0) now
// covers [1, 4e9+1) in both directions: every pixel from (1, 1) up, clipped to the window.
TEST(Pixels, HugeZoomCoversTheWindowWithoutOverflow) {
  Context ctx(test::small_config(6, 6));
  test::window_projection(ctx);
  ctx.glRasterPos2i(1, 1);
  ctx.glPixelZoom(4e9f, 4e9f);
  ctx.glDrawPixels(2, 2, GL_RGBA, GL_UNSIGNED_BYTE, kImage);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(pixel(ctx, 1, 1)[0], 10u);
  EXPECT_EQ(pixel(ctx, 5, 5)[0], 10u);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 0u);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 25u);  // the 5x5 pixels of group (0, 0)
  ctx.glPixelZoom(-4e9f, -4e9f);  // mirrored: [1 - 4e9, 1): pixel 0 only, in x and in y
  ctx.glDrawPixels(2, 2, GL_RGBA, GL_UNSIGNED_BYTE, kImage);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 10u);
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

TEST(Imaging, PaperFigure4CountsShadowedChannelsInAlpha) {
  // §3 of Brabec & Seidel: a colour table sends 0 -> 0 and anything above 0 -> 64/255
  // (63/255 in alpha), then the colour matrix sums the four channels into alpha. For each of
  // the 16 combinations of set channels the alpha code is 64·(R + G + B set) + 63·(A set):
  // 0 for none, 255 for all four. At 12 bits the constants are 1024 and 1023 -> 4095.
  for (int bits : {8, 12}) {
    const int levels = 1 << bits;
    const std::uint32_t full = static_cast<std::uint32_t>(levels - 1);
    const std::uint32_t quarter = static_cast<std::uint32_t>(levels / 4);  // 64 or 1024
    Context ctx(test::small_config(16, 2, bits));
    test::window_projection(ctx);
    // Source row: pixel m has channel k set (to the largest code) when bit k of m is set.
    std::vector<GLushort> src(16 * 4);
    for (int m = 0; m < 16; ++m)
      for (int k = 0; k < 4; ++k) src[static_cast<std::size_t>(4 * m + k)] = (m >> k) & 1 ? 65535 : 0;
    ctx.glRasterPos2i(0, 0);
    ctx.glDrawPixels(16, 1, GL_RGBA, GL_UNSIGNED_SHORT, src.data());
    // The table, one entry per code: entry 0 is 0, every other entry (q, q, q, q − 1)/(2^n − 1).
    std::vector<GLfloat> table(static_cast<std::size_t>(4 * levels), 0.0f);
    for (int i = 1; i < levels; ++i) {
      for (int k = 0; k < 3; ++k) table[static_cast<std::size_t>(4 * i + k)] = static_cast<float>(quarter) / static_cast<float>(full);
      table[static_cast<std::size_t>(4 * i + 3)] = static_cast<float>(quarter - 1) / static_cast<float>(full);
    }
    ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA, levels, GL_RGBA, GL_FLOAT, table.data());
    ctx.glEnable(GL_COLOR_TABLE);
    const double m[16] = {1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 0, 0, 0, 1};  // A' = R + G + B + A
    ctx.glMatrixMode(GL_COLOR);
    ctx.glLoadMatrixd(m);
    ctx.glRasterPos2i(0, 1);
    ctx.glCopyPixels(0, 0, 16, 1, GL_COLOR);
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    for (int mask = 0; mask < 16; ++mask) {
      const std::uint32_t rgb_set = static_cast<std::uint32_t>((mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1));
      const std::uint32_t expected = quarter * rgb_set + ((mask >> 3) & 1 ? quarter - 1 : 0);
      EXPECT_EQ(pixel(ctx, mask, 1)[3], expected) << "bits " << bits << " mask " << mask;
    }
    EXPECT_EQ(pixel(ctx, 15, 1)[3], full);
    EXPECT_EQ(ctx.total_counters().color_table_lookups, 16u);
  }
}

TEST(Imaging, ColorTableErrorsAndLimits) {
  Context ctx(test::small_config(2, 2));
  const GLubyte t[12] = {0};
  ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA, 3, GL_RGBA, GL_UNSIGNED_BYTE, t);  // not a power of two
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  ctx.glColorTable(GL_COLOR_TABLE, 4, 2, GL_RGBA, GL_UNSIGNED_BYTE, t);  // 1-4 are not accepted
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glColorTable(GL_TEXTURE_2D, GL_RGBA, 2, GL_RGBA, GL_UNSIGNED_BYTE, t);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA, 1 << 17, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);  // over the limit
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_TABLE_TOO_LARGE));
  ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA, 2, GL_RGBA, GL_UNSIGNED_BYTE, t);
  ctx.glColorSubTable(GL_COLOR_TABLE, 1, 2, GL_RGBA, GL_UNSIGNED_BYTE, t);  // 1 + 2 > 2
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  GLint w = 0;
  ctx.glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &w);
  EXPECT_EQ(w, 2);
}

namespace {
// A 3x3 RGBA float image whose components identify their source: R = 10x + y + 1,
// G = 100 + ..., scaled by 1/1000 so that they stay below 1.
std::vector<GLfloat> numbered_image(int w, int h) {
  std::vector<GLfloat> img(static_cast<std::size_t>(4 * w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 4; ++k)
        img[static_cast<std::size_t>(4 * (y * w + x) + k)] = static_cast<float>((100 * k + 10 * x + y + 1) / 1000.0);
  return img;
}
double numbered(int x, int y, int k) { return (100 * k + 10 * x + y + 1) / 1000.0; }
}  // namespace

TEST(Imaging, PaperSection4PackingKernel) {
  // §4's 3x3 RGBA filter, printed top row first in the paper; GL images (and filters) are
  // given bottom row first, so the filter data's row 0 is the printed bottom row
  // ([1,0,0,0] [0,1,0,0] [0,0,0,0]) and row 1 the printed middle row ([0,0,1,0] [0,0,0,1] 0).
  // Output texel (i, j) then holds R from (i−1, j−1) (lower left), G from (i, j−1) (lower),
  // B from (i−1, j) (left), A from (i, j) (centre). Drawn with DrawPixels at 16 bits so the
  // values survive the framebuffer exactly enough to compare codes.
  const GLfloat filter[3 * 3 * 4] = {1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 0, 0,    // row 0 (bottom)
                                     0, 0, 1, 0,  0, 0, 0, 1,  0, 0, 0, 0,    // row 1
                                     0, 0, 0, 0,  0, 0, 0, 0,  0, 0, 0, 0};   // row 2 (top)
  Context ctx(test::small_config(3, 3, 16));
  test::window_projection(ctx);
  ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, filter);
  ctx.glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  ctx.glEnable(GL_CONVOLUTION_2D);
  const std::vector<GLfloat> img = numbered_image(3, 3);
  ctx.glRasterPos2i(0, 0);
  ctx.glDrawPixels(3, 3, GL_RGBA, GL_FLOAT, img.data());
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  auto code = [](double v) { return static_cast<std::uint32_t>(std::floor(v * 65535.0 + 0.5)); };
  const auto p = pixel(ctx, 1, 1);
  EXPECT_EQ(p[0], code(numbered(0, 0, 0)));  // R from the lower left
  EXPECT_EQ(p[1], code(numbered(1, 0, 1)));  // G from below
  EXPECT_EQ(p[2], code(numbered(0, 1, 2)));  // B from the left
  EXPECT_EQ(p[3], code(numbered(1, 1, 3)));  // A from the centre
  EXPECT_EQ(ctx.total_counters().convolution_taps, 81u);  // 9 pixels x 9 taps
}

TEST(Imaging, ConvolutionBorderModesAndReduceSizes) {
  // A 1x3 box filter (weights 1/3) on a 3x1 image (0.3, 0.6, 0.9):
  //  REPLICATE: x=0: (0.3 + 0.3 + 0.6)/3 = 0.4; x=2: (0.6 + 0.9 + 0.9)/3 = 0.8.
  //  CONSTANT (border 0): x=0: (0 + 0.3 + 0.6)/3 = 0.3; x=2: (0.6 + 0.9 + 0)/3 = 0.5.
  //  REDUCE: one output pixel (0.3 + 0.6 + 0.9)/3 = 0.6, anchored at the raster position.
  const GLfloat box[3 * 4] = {1.f / 3, 1.f / 3, 1.f / 3, 1.f / 3, 1.f / 3, 1.f / 3, 1.f / 3, 1.f / 3,
                              1.f / 3, 1.f / 3, 1.f / 3, 1.f / 3};
  const GLfloat img[3] = {0.3f, 0.6f, 0.9f};
  struct Case { GLenum mode; double first, last; int drawn; };
  const Case cases[] = {{GL_REPLICATE_BORDER, 0.4, 0.8, 3}, {GL_CONSTANT_BORDER, 0.3, 0.5, 3}, {GL_REDUCE, 0.6, -1, 1}};
  for (const Case& c : cases) {
    Context ctx(test::small_config(3, 1, 12));
    test::window_projection(ctx);
    ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_LUMINANCE, 3, 1, GL_RGBA, GL_FLOAT, box);
    ctx.glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, static_cast<GLint>(c.mode));
    ctx.glEnable(GL_CONVOLUTION_2D);
    ctx.glRasterPos2i(0, 0);
    ctx.glDrawPixels(3, 1, GL_LUMINANCE, GL_FLOAT, img);
    // Luminance filter: R, G, B convolved with the filter's L; alpha (1) passes unchanged.
    // The inputs are floats (0.3f ...), so the sums are taken as the spec's Σ over the taps in
    // double: ((s0·t + s1·t) + s2·t) with t = float(1/3); none lies near a rounding tie.
    const double t = 1.0f / 3.0f, a = 0.3f, b = 0.6f, d = 0.9f;
    const double sums[3][2] = {{(a * t + a * t) + b * t, (b * t + d * t) + d * t},
                               {(0.0 * t + a * t) + b * t, (b * t + d * t) + 0.0 * t},
                               {(a * t + b * t) + d * t, 0.0}};
    const int row = c.mode == GL_REPLICATE_BORDER ? 0 : c.mode == GL_CONSTANT_BORDER ? 1 : 2;
    EXPECT_NEAR(sums[row][0], c.first, 1e-6);  // the hand values above
    EXPECT_EQ(pixel(ctx, 0, 0)[0], static_cast<std::uint32_t>(std::floor(sums[row][0] * 4095.0 + 0.5))) << enum_name(c.mode);
    if (c.last >= 0) {
      EXPECT_NEAR(sums[row][1], c.last, 1e-6);
      EXPECT_EQ(pixel(ctx, 2, 0)[0], static_cast<std::uint32_t>(std::floor(sums[row][1] * 4095.0 + 0.5))) << enum_name(c.mode);
    }
    EXPECT_EQ(pixel(ctx, 0, 0)[3], 4095u);
    EXPECT_EQ(ctx.total_counters().pixels_drawn, static_cast<std::uint64_t>(c.drawn));
  }
  // REDUCE to nothing: a 3x3 filter on a 2x2 image draws nothing, without an error.
  Context ctx(test::small_config(3, 3, 8));
  const GLfloat f9[9] = {0};
  ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_LUMINANCE, 3, 3, GL_LUMINANCE, GL_FLOAT, f9);
  ctx.glEnable(GL_CONVOLUTION_2D);
  const GLfloat four[4] = {1, 1, 1, 1};
  ctx.glDrawPixels(2, 2, GL_LUMINANCE, GL_FLOAT, four);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(ctx.total_counters().fragments_generated, 0u);
  // Over the profile's limit (ideal: 11).
  std::vector<GLfloat> big(13 * 13, 0.0f);
  ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_LUMINANCE, 13, 13, GL_LUMINANCE, GL_FLOAT, big.data());
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
}

TEST(Imaging, HistogramAndMinmaxOfAKnownImage) {
  // Luminance image 0, 1/3, 2/3, 1, 1 (as floats) drawn through a 4-entry LUMINANCE
  // histogram: indices round(v·3) = 0, 1, 2, 3, 3 -> counts 1, 1, 1, 2. Minmax (RGBA) sees
  // the unclamped red values after a bias of −0.5: min −0.5, max 0.5.
  Context ctx(test::small_config(5, 1));
  test::window_projection(ctx);
  ctx.glHistogram(GL_HISTOGRAM, 4, GL_LUMINANCE, GL_FALSE);
  ctx.glEnable(GL_HISTOGRAM);
  ctx.glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
  ctx.glEnable(GL_MINMAX);
  ctx.glPixelTransferf(GL_RED_BIAS, -0.5f);
  const GLfloat img[5] = {0.0f, 1.0f / 3, 2.0f / 3, 1.0f, 1.0f};
  ctx.glRasterPos2i(0, 0);
  ctx.glDrawPixels(5, 1, GL_LUMINANCE, GL_FLOAT, img);
  GLuint counts[4];
  ctx.glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_LUMINANCE, GL_UNSIGNED_INT, counts);
  // With the red bias the luminance (red) values are −0.5, −1/6, 1/6, 0.5, 0.5:
  // clamped then indexed: 0, 0, round(0.5) = 1 (ties up), round(1.5) = 2, 2.
  EXPECT_EQ(counts[0], 2u);
  EXPECT_EQ(counts[1], 1u);
  EXPECT_EQ(counts[2], 2u);
  EXPECT_EQ(counts[3], 0u);
  GLfloat mm[8];
  ctx.glGetMinmax(GL_MINMAX, GL_TRUE, GL_RGBA, GL_FLOAT, mm);
  EXPECT_FLOAT_EQ(mm[0], -0.5f);
  EXPECT_FLOAT_EQ(mm[4], 0.5f);
  EXPECT_FLOAT_EQ(mm[1], 0.0f);  // green: 0 .. 1
  EXPECT_FLOAT_EQ(mm[5], 1.0f);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 5u);  // no sink: the pixels are drawn
  // With a histogram sink nothing reaches the framebuffer; counting goes on.
  ctx.glHistogram(GL_HISTOGRAM, 4, GL_LUMINANCE, GL_TRUE);
  ctx.glDrawPixels(5, 1, GL_LUMINANCE, GL_FLOAT, img);
  ctx.glGetHistogram(GL_HISTOGRAM, GL_TRUE, GL_LUMINANCE, GL_UNSIGNED_INT, counts);
  EXPECT_EQ(counts[0] + counts[1] + counts[2] + counts[3], 5u);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 5u);
  ctx.glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_LUMINANCE, GL_UNSIGNED_INT, counts);
  EXPECT_EQ(counts[0] + counts[1] + counts[2] + counts[3], 0u);  // reset by the previous get
  ctx.glHistogram(GL_HISTOGRAM, 3, GL_LUMINANCE, GL_FALSE);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  ctx.glHistogram(GL_HISTOGRAM, 4, GL_INTENSITY, GL_FALSE);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}

TEST(Imaging, PixelMapColor) {
  // R_TO_R of size 3 {0, 0.25, 1}: red 0.5 -> index round(0.5·2) = 1 -> 0.25; 0.2 -> 0 -> 0.
  // Entries are clamped when given (A19): 1.5 -> 1. The other maps keep their initial {0}.
  Context ctx(test::small_config(2, 1));
  test::window_projection(ctx);
  const GLfloat map[3] = {0.0f, 0.25f, 1.5f};
  ctx.glPixelMapfv(GL_PIXEL_MAP_R_TO_R, 3, map);
  const GLfloat ones[1] = {1.0f};
  ctx.glPixelMapfv(GL_PIXEL_MAP_G_TO_G, 1, ones);
  ctx.glPixelMapfv(GL_PIXEL_MAP_B_TO_B, 1, ones);
  ctx.glPixelMapfv(GL_PIXEL_MAP_A_TO_A, 1, ones);
  ctx.glPixelTransferi(GL_MAP_COLOR, GL_TRUE);
  const GLfloat px[8] = {0.5f, 0, 0, 1, 0.9f, 0, 0, 1};
  ctx.glRasterPos2i(0, 0);
  ctx.glDrawPixels(2, 1, GL_RGBA, GL_FLOAT, px);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 64u);   // 0.25·255 = 63.75 -> 64
  EXPECT_EQ(pixel(ctx, 1, 0)[0], 255u);  // 0.9 -> index round(1.8) = 2 -> clamped 1.5 -> 1
  EXPECT_EQ(pixel(ctx, 0, 0)[1], 255u);
  EXPECT_EQ(ctx.total_counters().pixels_mapped, 2u);
  ctx.glPixelMapfv(GL_PIXEL_MAP_I_TO_R, 3, map);  // index maps must be 2^k
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  ctx.glPixelMapfv(GL_PIXEL_MAP_R_TO_R, 0, map);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  // The same map as unsigned ints (Table 2.6: c / (2^32 − 1)): 2^30 -> 0.25000000006 -> 64;
  // 2^32 − 1 -> 1 -> 255.
  const GLuint umap[3] = {0u, 1u << 30, 4294967295u};
  ctx.glPixelMapuiv(GL_PIXEL_MAP_R_TO_R, 3, umap);
  ctx.glRasterPos2i(0, 0);
  ctx.glDrawPixels(2, 1, GL_RGBA, GL_FLOAT, px);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 64u);
  EXPECT_EQ(pixel(ctx, 1, 0)[0], 255u);
}

// §3.7: a bitmap's set bits become fragments of the raster colour at ⌊x_rp − x_o⌋ + i,
// ⌊y_rp − y_o⌋ + j; the raster position then moves by (x_move, y_move). Bits are read MSB
// first unless UNPACK_LSB_FIRST; rows are padded to the unpack alignment.
TEST(Pixels, BitmapDrawsItsSetBitsAndMovesTheRasterPosition) {
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  ctx.glColor4ub(200, 0, 0, 255);
  ctx.glRasterPos2f(2.5f, 1.5f);   // raster colour: the current colour now
  ctx.glColor4ub(0, 200, 0, 255);  // does not change the raster colour
  ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const GLubyte bits[2] = {0xA0, 0x40};  // row 0: x = 0 and 2; row 1: x = 1
  ctx.glBitmap(3, 2, 0.5f, 0.5f, 4.0f, 1.0f, bits);
  // Lower left ⌊2.5 − 0.5⌋ = 2, ⌊1.5 − 0.5⌋ = 1: pixels (2, 1), (4, 1), (3, 2).
  EXPECT_EQ(pixel(ctx, 2, 1)[0], 200u);
  EXPECT_EQ(pixel(ctx, 4, 1)[0], 200u);
  EXPECT_EQ(pixel(ctx, 3, 2)[0], 200u);
  EXPECT_EQ(pixel(ctx, 3, 1)[0], 0u);
  EXPECT_EQ(pixel(ctx, 2, 2)[0], 0u);
  EXPECT_EQ(pixel(ctx, 3, 2)[1], 0u);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 3u);
  // The position is now (6.5, 2.5): a bitmap without data only moves it, by (−1, 2).
  GLfloat position[4] = {};
  ctx.glGetFloatv(GL_CURRENT_RASTER_POSITION, position);
  EXPECT_EQ(position[0], 6.5f);
  EXPECT_EQ(position[1], 2.5f);
  ctx.glBitmap(0, 0, 0, 0, -1.0f, 2.0f, nullptr);
  ctx.glPixelStorei(GL_UNPACK_LSB_FIRST, GL_TRUE);
  const GLubyte lsb[1] = {0x05};  // LSB first: x = 0 and 2
  ctx.glBitmap(3, 1, 0, 0, 0, 0, lsb);
  // At (5.5, 4.5): pixels (5, 4) and (7, 4).
  EXPECT_EQ(pixel(ctx, 5, 4)[0], 200u);
  EXPECT_EQ(pixel(ctx, 7, 4)[0], 200u);
  EXPECT_EQ(pixel(ctx, 6, 4)[0], 0u);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 5u);
  ctx.glBitmap(-1, 1, 0, 0, 0, 0, lsb);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
}

TEST(Pixels, BitmapAtAnInvalidRasterPositionDoesNothing) {
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  ctx.glRasterPos2f(-5.0f, 2.0f);  // outside the clip volume: invalid
  const GLubyte bits[1] = {0xFF};
  ctx.glBitmap(8, 1, 0, 0, 10.0f, 0, bits);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 0u);
  GLint valid = 1;
  ctx.glGetIntegerv(GL_CURRENT_RASTER_POSITION_VALID, &valid);
  EXPECT_EQ(valid, 0);
}

TEST(Imaging, TheWholeChainOnASmallImage) {
  // Every RGBA transfer stage at once on a 2x1 FLOAT image, values by hand (all exact binary
  // fractions until the final conversion):
  //  p0 = (0.25, 0.5, 0.75, 1), p1 = (0.5, 0.25, 0, 0.5)
  //  red scale 2, bias −0.25:                   p0.r = 0.25, p1.r = 0.75
  //  COLOR_TABLE RGB, 8 entries i/8, index round(c·7): p0 = (2/8, 4/8, 5/8, 1), p1 = (5/8, 2/8, 0, 0.5)
  //  2x1 convolution (½, ½), REDUCE -> 1x1:     (7/16, 3/8, 5/16, 3/4)
  //  post-convolution green scale 2:            g = 3/4
  //  POST_CONVOLUTION table ALPHA {0, ½}:       a: round(0.75) = 1 -> ½
  //  colour matrix swapping R and B:            (5/16, 3/4, 7/16, ½)
  //  post-matrix alpha bias ¼:                  a = ¾
  //  POST_COLOR_MATRIX table LUMINANCE, 32 entries 1 − i/32, index round(c·31):
  //    r: 9.6875 -> 10 -> 11/16; g: 23.25 -> 23 -> 9/32; b: 13.5625 -> 14 -> 9/16; a stays ¾
  //  histogram (4, RGBA): indices round(c·3) = 2, 1, 2, 2; minmax = the pixel itself.
  //  8 bits: 175.3125, 71.71875, 143.4375, 191.25 -> 175, 72, 143, 191
  //  12 bits: 2815.3125, 1151.71875, 2303.4375, 3071.25 -> 2815, 1152, 2303, 3071
  const std::uint32_t expected[2][4] = {{175, 72, 143, 191}, {2815, 1152, 2303, 3071}};
  for (int b = 0; b < 2; ++b) {
    const int bits = b ? 12 : 8;
    Context ctx(test::small_config(2, 1, bits));
    test::window_projection(ctx);
    ctx.glPixelTransferf(GL_RED_SCALE, 2.0f);
    ctx.glPixelTransferf(GL_RED_BIAS, -0.25f);
    GLfloat table0[8 * 3];
    for (int i = 0; i < 8; ++i) table0[3 * i] = table0[3 * i + 1] = table0[3 * i + 2] = static_cast<GLfloat>(i) / 8;
    ctx.glColorTable(GL_COLOR_TABLE, GL_RGB, 8, GL_RGB, GL_FLOAT, table0);
    ctx.glEnable(GL_COLOR_TABLE);
    const GLfloat taps[8] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 2, 1, GL_RGBA, GL_FLOAT, taps);
    ctx.glEnable(GL_CONVOLUTION_2D);
    ctx.glPixelTransferf(GL_POST_CONVOLUTION_GREEN_SCALE, 2.0f);
    const GLfloat table1[2] = {0.0f, 0.5f};
    ctx.glColorTable(GL_POST_CONVOLUTION_COLOR_TABLE, GL_ALPHA, 2, GL_ALPHA, GL_FLOAT, table1);
    ctx.glEnable(GL_POST_CONVOLUTION_COLOR_TABLE);
    const GLfloat swap_rb[16] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1};  // column-major
    ctx.glMatrixMode(GL_COLOR);
    ctx.glLoadMatrixf(swap_rb);
    ctx.glMatrixMode(GL_MODELVIEW);
    ctx.glPixelTransferf(GL_POST_COLOR_MATRIX_ALPHA_BIAS, 0.25f);
    GLfloat table2[32];
    for (int i = 0; i < 32; ++i) table2[i] = 1.0f - static_cast<GLfloat>(i) / 32;
    ctx.glColorTable(GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_LUMINANCE, 32, GL_LUMINANCE, GL_FLOAT, table2);
    ctx.glEnable(GL_POST_COLOR_MATRIX_COLOR_TABLE);
    ctx.glHistogram(GL_HISTOGRAM, 4, GL_RGBA, GL_FALSE);
    ctx.glEnable(GL_HISTOGRAM);
    ctx.glMinmax(GL_MINMAX, GL_RGBA, GL_FALSE);
    ctx.glEnable(GL_MINMAX);
    ASSERT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    const GLfloat image[8] = {0.25f, 0.5f, 0.75f, 1.0f, 0.5f, 0.25f, 0.0f, 0.5f};
    ctx.glRasterPos2i(0, 0);
    ctx.glDrawPixels(2, 1, GL_RGBA, GL_FLOAT, image);
    EXPECT_EQ(test::pixel(ctx, 0, 0), (std::array<std::uint32_t, 4>{expected[b][0], expected[b][1], expected[b][2],
                                                                    expected[b][3]}))
        << bits << " bits";
    EXPECT_EQ(test::pixel(ctx, 1, 0), (std::array<std::uint32_t, 4>{0, 0, 0, 0}));  // REDUCE: one pixel drawn
    GLuint counts[16];
    ctx.glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, counts);
    const GLuint expected_counts[16] = {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 0, 0, 0};
    for (int i = 0; i < 16; ++i) EXPECT_EQ(counts[i], expected_counts[i]) << "histogram entry " << i / 4 << "." << i % 4;
    GLfloat mm[8];
    ctx.glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, GL_FLOAT, mm);
    const GLfloat pixel[4] = {11.0f / 16, 9.0f / 32, 9.0f / 16, 0.75f};
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(mm[k], pixel[k]) << "min " << k;
      EXPECT_EQ(mm[4 + k], pixel[k]) << "max " << k;
    }
    const Counters t = ctx.total_counters();
    EXPECT_EQ(t.pixels_scale_bias, 2u);
    EXPECT_EQ(t.color_table_lookups, 2u);
    EXPECT_EQ(t.convolution_taps, 2u);
    EXPECT_EQ(t.post_convolution_table_lookups, 1u);
    EXPECT_EQ(t.pixels_color_matrix, 1u);
    EXPECT_EQ(t.post_color_matrix_table_lookups, 1u);
    EXPECT_EQ(t.histogram_updates, 1u);
    EXPECT_EQ(t.minmax_updates, 1u);
  }
}

TEST(Pixels, BandedCopyEqualsTheWholeRectangleCopy) {
  // glCopyPixels without a convolution converts, transfers and draws 16 rows at a time; with
  // a 1x1 identity convolution (c·1 + 0 = c exactly for these non-negative values) it takes
  // the whole rectangle at once. A 37-row copy with zoom 1.5 x −0.75, a colour table, the
  // colour matrix and a histogram must give the same planes and the same counts both ways.
  auto run = [](bool whole, std::vector<std::uint16_t>& plane, std::vector<GLuint>& counts) {
    Context ctx(test::small_config(64, 80, 12));
    test::window_projection(ctx);
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 30; ++x) {
        ctx.glColor4f(static_cast<float>(x) / 30, static_cast<float>(y) / 40, static_cast<float>((x * y) % 7) / 7, 0.5f);
        ctx.glRectf(static_cast<float>(x), static_cast<float>(y), static_cast<float>(x + 1), static_cast<float>(y + 1));
      }
    std::vector<GLfloat> table(64 * 4);
    for (std::size_t i = 0; i < table.size(); ++i) table[i] = static_cast<GLfloat>((i * 37) % 64) / 63;
    ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA, 64, GL_RGBA, GL_FLOAT, table.data());
    ctx.glEnable(GL_COLOR_TABLE);
    const GLfloat m[16] = {0.5f, 0.25f, 0, 0.25f, 0.25f, 0.5f, 0.25f, 0.25f, 0, 0.25f, 0.5f, 0.25f, 0, 0, 0, 0.25f};
    ctx.glMatrixMode(GL_COLOR);
    ctx.glLoadMatrixf(m);
    ctx.glMatrixMode(GL_MODELVIEW);
    ctx.glHistogram(GL_HISTOGRAM, 8, GL_RGBA, GL_FALSE);
    ctx.glEnable(GL_HISTOGRAM);
    if (whole) {
      const GLfloat one[4] = {1, 1, 1, 1};
      ctx.glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 1, 1, GL_RGBA, GL_FLOAT, one);
      ctx.glEnable(GL_CONVOLUTION_2D);
    }
    ctx.glPixelZoom(1.5f, -0.75f);
    ctx.glRasterPos2i(5, 79);
    ctx.glCopyPixels(0, 0, 30, 37, GL_COLOR);
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    plane = ctx.framebuffer().color[0].rgba;
    counts.assign(32, 0);
    ctx.glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGBA, GL_UNSIGNED_INT, counts.data());
    const Counters t = ctx.total_counters();
    return std::array<std::uint64_t, 5>{t.fragments_generated, t.fragments_written, t.pixels_drawn, t.color_table_lookups,
                                        t.pixels_color_matrix};
  };
  std::vector<std::uint16_t> banded_plane, whole_plane;
  std::vector<GLuint> banded_counts, whole_counts;
  const auto banded = run(false, banded_plane, banded_counts);
  const auto whole = run(true, whole_plane, whole_counts);
  EXPECT_EQ(banded_plane, whole_plane);
  EXPECT_EQ(banded_counts, whole_counts);
  EXPECT_EQ(banded, whole);
  EXPECT_EQ(banded[2], 30u * 37u);
}

namespace {

// The per-component transfer of the two tests below, and its value for one component worked
// from §3.6.5 in doubles: step 2 scale and bias, step 3 MAP_COLOR (clamp, index
// ⌊c·(size − 1) + ½⌋), step 4 COLOR_TABLE (RGBA, 64 entries, the same index rule), step 8
// POST_COLOR_MATRIX_COLOR_TABLE (LUMINANCE, 16 entries: R, G and B each from its own index,
// alpha untouched).
struct PerComponentTransfer {
  float scale[4] = {1.5f, 1.0f, 0.75f, 4096.0f}, bias[4] = {0.0f, -0.2f, 0.1f, 0.0f};
  std::vector<float> maps[4] = {{0.1f, 0.9f, 0.3f, 0.7f, 0.2f, 1.0f, 0.0f, 0.55f},
                                {0.25f, 0.5f, 0.75f, 1.0f},
                                {0.0f, 0.05f, 0.1f, 0.2f, 0.3f, 0.35f, 0.4f, 0.5f, 0.6f, 0.65f, 0.7f, 0.8f, 0.85f,
                                 0.9f, 0.95f, 1.0f},
                                {0.0f, 1.0f}};
  std::vector<float> table = std::vector<float>(64 * 4), post = std::vector<float>(16);
  bool map = false;
  PerComponentTransfer() {
    for (std::size_t i = 0; i < table.size(); ++i) table[i] = static_cast<float>((i * 37) % 64) / 63.0f;
    for (std::size_t i = 0; i < post.size(); ++i) post[i] = static_cast<float>((i * 5) % 16) / 15.0f;
  }
  void apply(Context& ctx) const {
    const GLenum scales[4] = {GL_RED_SCALE, GL_GREEN_SCALE, GL_BLUE_SCALE, GL_ALPHA_SCALE};
    const GLenum biases[4] = {GL_RED_BIAS, GL_GREEN_BIAS, GL_BLUE_BIAS, GL_ALPHA_BIAS};
    const GLenum map_names[4] = {GL_PIXEL_MAP_R_TO_R, GL_PIXEL_MAP_G_TO_G, GL_PIXEL_MAP_B_TO_B, GL_PIXEL_MAP_A_TO_A};
    for (int k = 0; k < 4; ++k) {
      ctx.glPixelTransferf(scales[k], scale[k]);
      ctx.glPixelTransferf(biases[k], bias[k]);
      ctx.glPixelMapfv(map_names[k], static_cast<GLsizei>(maps[k].size()), maps[k].data());
    }
    ctx.glPixelTransferi(GL_MAP_COLOR, map ? GL_TRUE : GL_FALSE);
    ctx.glColorTable(GL_COLOR_TABLE, GL_RGBA, 64, GL_RGBA, GL_FLOAT, table.data());
    ctx.glEnable(GL_COLOR_TABLE);
    ctx.glColorTable(GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_LUMINANCE, 16, GL_LUMINANCE, GL_FLOAT, post.data());
    ctx.glEnable(GL_POST_COLOR_MATRIX_COLOR_TABLE);
  }
  static std::size_t index(double v, std::size_t size) {
    return static_cast<std::size_t>(std::floor(std::clamp(v, 0.0, 1.0) * static_cast<double>(size - 1) + 0.5));
  }
  double value(int k, std::uint32_t code, int bits) const {
    double v = static_cast<double>(code) / ((1 << bits) - 1);
    v = v * static_cast<double>(scale[k]) + static_cast<double>(bias[k]);
    if (map) v = maps[k][index(v, maps[k].size())];
    v = table[4 * index(v, 64) + static_cast<std::size_t>(k)];
    if (k < 3) v = post[index(v, 16)];
    return v;
  }
  static std::uint32_t code(double v, int bits) {
    return static_cast<std::uint32_t>(std::floor(std::clamp(v, 0.0, 1.0) * ((1 << bits) - 1) + 0.5));
  }
};

// A 128x64 12-bit window of varied codes (each channel from its own hash of the pixel), its
// codes as drawn, and the transfer set, on `threads` threads.
struct TransferredWindow {
  Context ctx{test::small_config(128, 64, 12)};
  std::vector<std::uint16_t> source;
  PerComponentTransfer transfer;
  TransferredWindow(int threads, bool map) {
    ctx.set_threads(threads);
    test::window_projection(ctx);
    std::vector<GLushort> image(4 * 128 * 64);
    for (std::size_t i = 0; i < image.size(); ++i) image[i] = static_cast<GLushort>((i * 2654435761u) >> 13);
    ctx.glRasterPos2i(0, 0);
    ctx.glDrawPixels(128, 64, GL_RGBA, GL_UNSIGNED_SHORT, image.data());
    source = ctx.framebuffer().color[0].rgba;
    transfer.map = map;
    transfer.apply(ctx);
  }
};

}  // namespace

TEST(Pixels, CopyPixelsThroughAPerComponentTransferMatchesTheSpecFormulas) {
  // Every step of this transfer takes a component through a function of that component alone,
  // so a copy of more pixels than the 4,097 codes (and the outside) of a 12-bit window finds
  // each code's result once (Context::copy_pixels_through_table); a smaller one converts each
  // pixel. Both must give what the formulas give the source's codes, on one thread and two.
  // The big copy moves the window up one row onto itself: each band must read its rows before
  // the band below writes them (a copy of the source first; a mutation skipping it smears row
  // 0 upwards), while the in-place copies read the window directly.
  for (const bool map : {false, true})
    for (const int threads : {1, 2})
      for (const auto& [width, height, dy] : {std::array<int, 3>{128, 60, 1}, std::array<int, 3>{128, 60, 0},
                                              std::array<int, 3>{9, 7, 0}}) {
        TransferredWindow window(threads, map);
        Context& ctx = window.ctx;
        const std::vector<std::uint16_t>& source = window.source;
        const PerComponentTransfer& transfer = window.transfer;
        const Counters before = ctx.total_counters();
        ctx.glRasterPos2i(0, dy);
        ctx.glCopyPixels(0, 0, width, height, GL_COLOR);
        ASSERT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
        int wrong = 0;
        for (int y = 0; y < 64; ++y)
          for (int x = 0; x < 128; ++x) {
            const bool copied = x < width && y >= dy && y < dy + height;
            const std::size_t from = 4 * (static_cast<std::size_t>(copied ? y - dy : y) * 128 + static_cast<std::size_t>(x));
            const auto got = test::pixel(ctx, x, y);
            for (int k = 0; k < 4; ++k) {
              const std::uint32_t c = source[from + static_cast<std::size_t>(k)];
              const std::uint32_t want = copied ? PerComponentTransfer::code(transfer.value(k, c, 12), 12) : c;
              if (got[static_cast<std::size_t>(k)] != want && ++wrong <= 3)
                ADD_FAILURE() << "map " << map << " threads " << threads << " copy " << width << "x" << height
                              << " pixel (" << x << ", " << y << ") component " << k << ": " << got[static_cast<std::size_t>(k)]
                              << ", want " << want;
            }
          }
        EXPECT_EQ(wrong, 0);
        const Counters t = ctx.total_counters();
        const std::uint64_t n = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
        EXPECT_EQ(t.pixels_transferred - before.pixels_transferred, n);
        EXPECT_EQ(t.pixels_scale_bias - before.pixels_scale_bias, n);
        EXPECT_EQ(t.pixels_mapped - before.pixels_mapped, map ? n : 0u);
        EXPECT_EQ(t.color_table_lookups - before.color_table_lookups, n);
        EXPECT_EQ(t.post_color_matrix_table_lookups - before.post_color_matrix_table_lookups, n);
        EXPECT_EQ(t.pixels_color_matrix - before.pixels_color_matrix, 0u);
        EXPECT_EQ(t.fragments_written - before.fragments_written, n);
      }
}

TEST(Pixels, CopyTexImageThroughAPerComponentTransferMatchesTheSpecFormulas) {
  // The same transfer on the way into a LUMINANCE8_ALPHA8 texture (Table 3.15: L from R, A
  // from A, each rounded to 8 bits): 128x64 texels (more than the codes: looked up per texel)
  // and 8x4 (converted per texel), on one thread and two.
  for (const int threads : {1, 2})
    for (const auto& [width, height] : {std::array<int, 2>{128, 64}, std::array<int, 2>{8, 4}}) {
      TransferredWindow window(threads, true);
      Context& ctx = window.ctx;
      const std::vector<std::uint16_t>& source = window.source;
      const PerComponentTransfer& transfer = window.transfer;
      GLuint tex = 0;
      ctx.glGenTextures(1, &tex);
      ctx.glBindTexture(GL_TEXTURE_2D, tex);
      ctx.glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE8_ALPHA8, 0, 0, width, height, 0);
      ASSERT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
      std::vector<GLubyte> texels(2 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
      ctx.glPixelTransferi(GL_MAP_COLOR, GL_FALSE);  // read back unchanged: identity transfer
      ctx.glDisable(GL_COLOR_TABLE);
      ctx.glDisable(GL_POST_COLOR_MATRIX_COLOR_TABLE);
      for (const GLenum s : {GL_RED_SCALE, GL_GREEN_SCALE, GL_BLUE_SCALE, GL_ALPHA_SCALE}) ctx.glPixelTransferf(s, 1.0f);
      for (const GLenum b : {GL_RED_BIAS, GL_GREEN_BIAS, GL_BLUE_BIAS, GL_ALPHA_BIAS}) ctx.glPixelTransferf(b, 0.0f);
      ctx.glGetTexImage(GL_TEXTURE_2D, 0, GL_LUMINANCE_ALPHA, GL_UNSIGNED_BYTE, texels.data());
      int wrong = 0;
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const std::size_t from = 4 * (static_cast<std::size_t>(y) * 128 + static_cast<std::size_t>(x));
          const std::size_t at = 2 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x));
          const std::uint32_t want_l = PerComponentTransfer::code(transfer.value(0, source[from], 12), 8);
          const std::uint32_t want_a = PerComponentTransfer::code(transfer.value(3, source[from + 3], 12), 8);
          if ((texels[at] != want_l || texels[at + 1] != want_a) && ++wrong <= 3)
            ADD_FAILURE() << "threads " << threads << " copy " << width << "x" << height << " texel (" << x << ", " << y
                          << "): L " << int{texels[at]} << " A " << int{texels[at + 1]} << ", want " << want_l << " "
                          << want_a;
        }
      EXPECT_EQ(wrong, 0);
    }
}

// Issue 21, "work proportional to what is drawn": a copy 2^31 − 1 pixels long draws the few
// groups that land in the window, each where the whole rectangle would put it, and reads no
// more than those. The window holds red = 1 + x + 6y (drawn first); expected values by hand.
TEST(Pixels, HugeCopyPixelsIsClippedToTheWindowBeforeAnythingIsRead) {
  Context ctx(test::small_config(6, 6));
  test::window_projection(ctx);
  std::vector<GLubyte> image(6 * 6 * 4, 255);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) image[static_cast<std::size_t>(4 * (x + 6 * y))] = static_cast<GLubyte>(1 + x + 6 * y);
  ctx.glRasterPos2i(0, 0);
  ctx.glDrawPixels(6, 6, GL_RGBA, GL_UNSIGNED_BYTE, image.data());
  const Counters before = ctx.total_counters();
  // Zoom 1 from raster position (2, 1): group i lands on pixel (2 + i, 1); i = 0..3 are in the
  // window, so row 1 becomes 7, 8 (untouched), then source row 0's 1, 2, 3, 4.
  ctx.glRasterPos2i(2, 1);
  ctx.glCopyPixels(0, 0, 2147483647, 1, GL_COLOR);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  const unsigned row1[6] = {7, 8, 1, 2, 3, 4};
  for (int x = 0; x < 6; ++x) EXPECT_EQ(pixel(ctx, x, 1)[0], row1[x]) << "x " << x;
  const Counters after = ctx.total_counters();
  EXPECT_EQ(after.fragments_generated - before.fragments_generated, 4u);
  EXPECT_LE(after.pixels_read - before.pixels_read, 6u);  // a window row at most, not 2^31
  // Mirrored in y from (0, 5): group j covers rows [4 − j, 5 − j), so source column 3's rows
  // 0..4 (red 4, then 2 as the copy above left it, 16, 22, 28) land on column 0's rows 4 down to 0.
  ctx.glPixelZoom(1, -1);
  ctx.glRasterPos2i(0, 5);
  ctx.glCopyPixels(3, 0, 1, 2147483647, GL_COLOR);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  const unsigned column0[5] = {28, 22, 16, 2, 4};  // rows 0..4
  for (int y = 0; y < 5; ++y) EXPECT_EQ(pixel(ctx, 0, y)[0], column0[y]) << "y " << y;
  EXPECT_EQ(pixel(ctx, 0, 5)[0], 31u);  // row 5 is no group's: untouched (1 + 0 + 30)
  // A source far outside the window: its pixels are undefined (passim reads 0), still drawn
  // where they land, (2..5, 1) from (2, 1).
  ctx.glPixelZoom(1, 1);
  ctx.glRasterPos2i(2, 1);
  ctx.glCopyPixels(-2147483647 - 1, 0, 2147483647, 1, GL_COLOR);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  for (int x = 2; x < 6; ++x) EXPECT_EQ(pixel(ctx, x, 1)[0], 0u) << "x " << x;
  EXPECT_EQ(pixel(ctx, 1, 1)[0], 8u);
}

// glDrawPixels unpacks only the groups that can land in the window, entering the image further
// on (§3.6.4: SKIP_PIXELS grows, the row length stays the image's). A 5x2 image of RGBA bytes
// with SKIP_PIXELS 1 (row length = width 5), red = 10 + k for memory group k: group (i, j) is
// memory group 5j + 1 + i, and lands on (−2 + i, j); i = 2..4 are in the window.
TEST(Pixels, DrawPixelsPartlyOutsideTheWindowReadsTheSameGroups) {
  Context ctx(test::small_config(6, 6));
  test::window_projection(ctx);
  std::vector<GLubyte> image(11 * 4, 255);
  for (int k = 0; k < 11; ++k) image[static_cast<std::size_t>(4 * k)] = static_cast<GLubyte>(10 + k);
  ctx.glRasterPos2i(0, 0);
  ctx.glBitmap(0, 0, 0, 0, -2, 0, nullptr);  // the raster position moves to x = −2, still valid
  ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  ctx.glPixelStorei(GL_UNPACK_SKIP_PIXELS, 1);
  const Counters before = ctx.total_counters();
  ctx.glDrawPixels(5, 2, GL_RGBA, GL_UNSIGNED_BYTE, image.data());
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  const unsigned row0[4] = {13, 14, 15, 0}, row1[4] = {18, 19, 20, 0};
  for (int x = 0; x < 4; ++x) {
    EXPECT_EQ(pixel(ctx, x, 0)[0], row0[x]) << "x " << x;
    EXPECT_EQ(pixel(ctx, x, 1)[0], row1[x]) << "x " << x;
  }
  const Counters after = ctx.total_counters();
  EXPECT_EQ(after.fragments_generated - before.fragments_generated, 6u);
  EXPECT_LT(after.pixels_drawn - before.pixels_drawn, 10u);  // not all 5x2 groups were unpacked
}
