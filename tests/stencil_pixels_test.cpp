// Stencil-index rectangles (§3.6.4, §3.6.5 "arithmetic on indices", §4.3.1, §4.3.2 Table 4.6):
// glDrawPixels / glReadPixels with STENCIL_INDEX and glCopyPixels(GL_STENCIL), values by hand.
#include <gtest/gtest.h>

#include <vector>

#include "test_util.hpp"

using namespace passim;

namespace {

std::uint8_t stencil(const Context& ctx, int x, int y) {
  return ctx.framebuffer().stencil[ctx.framebuffer().pixel_index(x, y)];
}

void at_origin(Context& ctx) {
  test::window_projection(ctx);
  ctx.glRasterPos2i(0, 0);
}

}  // namespace

TEST(StencilPixels, DrawPixelsWritesThroughTheWritemaskOnly) {
  Context ctx(test::small_config(3, 2));
  at_origin(ctx);
  ctx.glClearStencil(0xA0);
  ctx.glClear(GL_STENCIL_BUFFER_BIT);
  ctx.glStencilMask(0x0F);
  // The per-fragment tests do not apply (§4.3.1): a stencil test that fails everything and a
  // depth test that fails everything change nothing.
  ctx.glEnable(GL_STENCIL_TEST);
  ctx.glStencilFunc(GL_NEVER, 0, 0xFF);
  ctx.glEnable(GL_DEPTH_TEST);
  ctx.glDepthFunc(GL_NEVER);
  ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const GLubyte indices[6] = {1, 0x37, 255, 16, 0x8F, 2};  // rows bottom first
  ctx.glDrawPixels(3, 2, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, indices);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  // (0xA0 & 0xF0) | (v & 0x0F)
  const std::uint8_t expected[6] = {0xA1, 0xA7, 0xAF, 0xA0, 0xAF, 0xA2};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) EXPECT_EQ(stencil(ctx, x, y), expected[3 * y + x]) << x << "," << y;
  const Counters t = ctx.total_counters();
  EXPECT_EQ(t.stencil_bits_written, 6u * 8u + 6u * 8u);  // the clear, then the rectangle
  EXPECT_EQ(t.fragments_generated, 0u);  // window coordinates and indices, not fragments
}

TEST(StencilPixels, IndexShiftOffsetAndFloatIndices) {
  Context ctx(test::small_config(4, 1));
  at_origin(ctx);
  // Shift 2, offset 3: 5 -> 23. Offset −10: 3 -> −7 -> 249 (mod 256).
  ctx.glPixelTransferi(GL_INDEX_SHIFT, 2);
  ctx.glPixelTransferi(GL_INDEX_OFFSET, 3);
  const GLuint a[1] = {5};
  ctx.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_INT, a);
  EXPECT_EQ(stencil(ctx, 0, 0), 23);
  ctx.glPixelTransferi(GL_INDEX_SHIFT, 0);
  ctx.glPixelTransferi(GL_INDEX_OFFSET, -10);
  const GLshort b[1] = {3};
  ctx.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_SHORT, b);
  EXPECT_EQ(stencil(ctx, 0, 0), 249);
  // A right shift keeps the fraction; the integer part is the floor: 5 >> 1 = 2.5 -> 2, and a
  // FLOAT index −0.5 -> −1 -> 255, 2.75 -> 2.
  ctx.glPixelTransferi(GL_INDEX_OFFSET, 0);
  ctx.glPixelTransferi(GL_INDEX_SHIFT, -1);
  const GLubyte c[1] = {5};
  ctx.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, c);
  EXPECT_EQ(stencil(ctx, 0, 0), 2);
  ctx.glPixelTransferi(GL_INDEX_SHIFT, 0);
  const GLfloat d[4] = {-0.5f, 2.75f, 300.0f, 1e30f};  // 300 -> 44; 1e30 is even past 2^8: 0
  ctx.glDrawPixels(4, 1, GL_STENCIL_INDEX, GL_FLOAT, d);
  EXPECT_EQ(stencil(ctx, 0, 0), 255);
  EXPECT_EQ(stencil(ctx, 1, 0), 2);
  EXPECT_EQ(stencil(ctx, 2, 0), 44);
  EXPECT_EQ(stencil(ctx, 3, 0), 0);
  // A shift too large for any index: saturated, not an undefined conversion; the index is
  // infinite and has no integer part (A27): 0.
  ctx.glPixelTransferf(GL_INDEX_SHIFT, 1e30f);
  ctx.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, c);
  EXPECT_EQ(stencil(ctx, 0, 0), 0);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(StencilPixels, MapStencilLooksUpTheIndexModuloTheMapSize) {
  Context ctx(test::small_config(2, 1));
  at_origin(ctx);
  const GLuint map[4] = {7, 9, 11, 13};
  ctx.glPixelMapuiv(GL_PIXEL_MAP_S_TO_S, 4, map);
  ctx.glPixelTransferi(GL_MAP_STENCIL, GL_TRUE);
  const GLubyte indices[2] = {6, 1};  // 6 mod 4 = 2 -> 11; 1 -> 9
  ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  ctx.glDrawPixels(2, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, indices);
  EXPECT_EQ(stencil(ctx, 0, 0), 11);
  EXPECT_EQ(stencil(ctx, 1, 0), 9);
  EXPECT_EQ(ctx.total_counters().pixels_mapped, 2u);
}

TEST(StencilPixels, ZoomScissorAndNarrowStencil) {
  FramebufferConfig cfg = test::small_config(4, 4);
  cfg.stencil_bits = 1;
  Context ctx(cfg);
  at_origin(ctx);
  ctx.glPixelZoom(2.0f, 2.0f);
  ctx.glEnable(GL_SCISSOR_TEST);
  ctx.glScissor(0, 0, 3, 4);  // column 3 is cut
  const GLubyte index[1] = {3};  // one bit: 3 & 1 = 1
  ctx.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, index);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(stencil(ctx, x, y), x < 2 && y < 2 ? 1 : 0) << x << "," << y;
  ctx.glRasterPos2i(2, 2);
  ctx.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, index);
  EXPECT_EQ(stencil(ctx, 2, 2), 1);
  EXPECT_EQ(stencil(ctx, 2, 3), 1);
  EXPECT_EQ(stencil(ctx, 3, 2), 0);  // scissored
  EXPECT_EQ(ctx.total_counters().stencil_bits_written, 4u + 2u);
}

TEST(StencilPixels, ReadPixelsMasksByTheType) {
  Context ctx(test::small_config(2, 1));
  ctx.glClearStencil(201);
  ctx.glClear(GL_STENCIL_BUFFER_BIT);
  GLubyte ub[2] = {};
  GLbyte b[2] = {};
  GLfloat f[2] = {};
  ctx.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  ctx.glReadPixels(0, 0, 2, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, ub);
  ctx.glReadPixels(0, 0, 2, 1, GL_STENCIL_INDEX, GL_BYTE, b);  // 201 & 127 = 73
  ctx.glReadPixels(0, 0, 2, 1, GL_STENCIL_INDEX, GL_FLOAT, f);
  EXPECT_EQ(ub[1], 201);
  EXPECT_EQ(b[1], 73);
  EXPECT_EQ(f[1], 201.0f);
  // Shift −1: 100.5 -> 100 as UNSIGNED_BYTE and as FLOAT (the integer index).
  ctx.glPixelTransferi(GL_INDEX_SHIFT, -1);
  ctx.glReadPixels(0, 0, 2, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, ub);
  ctx.glReadPixels(0, 0, 2, 1, GL_STENCIL_INDEX, GL_FLOAT, f);
  EXPECT_EQ(ub[0], 100);
  EXPECT_EQ(f[0], 100.0f);
  // Outside the window: 0.
  GLushort us[2] = {9, 9};
  ctx.glPixelTransferi(GL_INDEX_SHIFT, 0);
  ctx.glReadPixels(1, 0, 2, 1, GL_STENCIL_INDEX, GL_UNSIGNED_SHORT, us);
  EXPECT_EQ(us[0], 201);
  EXPECT_EQ(us[1], 0);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(StencilPixels, CopyPixelsReadsTheWholeSourceFirst) {
  // A22: an overlapping copy reads its source before writing: copying [0, 3) to x = 1 with
  // offset 1 gives 0: s0, 1: s0 + 1, 2: s1 + 1, 3: s2 + 1.
  Context ctx(test::small_config(4, 1));
  at_origin(ctx);
  ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  const GLubyte source[4] = {10, 20, 30, 40};
  ctx.glDrawPixels(4, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, source);
  ctx.glRasterPos2i(1, 0);
  ctx.glPixelTransferi(GL_INDEX_OFFSET, 1);
  ctx.glCopyPixels(0, 0, 3, 1, GL_STENCIL);
  EXPECT_EQ(stencil(ctx, 0, 0), 10);
  EXPECT_EQ(stencil(ctx, 1, 0), 11);
  EXPECT_EQ(stencil(ctx, 2, 0), 21);
  EXPECT_EQ(stencil(ctx, 3, 0), 31);
  EXPECT_EQ(ctx.total_counters().stencil_bits_read, 3u * 8u);
}

TEST(StencilPixels, ErrorsWithoutAStencilPlane) {
  FramebufferConfig cfg = test::small_config(2, 2);
  cfg.stencil_bits = 0;
  Context ctx(cfg);
  const GLubyte data[4] = {};
  GLubyte out[4] = {};
  ctx.glDrawPixels(1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, data);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  ctx.glReadPixels(0, 0, 1, 1, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, out);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  ctx.glCopyPixels(0, 0, 1, 1, GL_STENCIL);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  Context with(test::small_config(2, 2));
  with.glReadPixels(0, 0, 1, 1, GL_STENCIL_INDEX, GL_DOUBLE, out);
  EXPECT_EQ(with.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}
