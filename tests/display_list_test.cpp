// Display lists (§5.4) and vertex arrays (§2.8).
#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {
void quad(Context& c, float x0, float y0, float x1, float y1) {
  c.glBegin(GL_QUADS);
  c.glVertex2f(x0, y0);
  c.glVertex2f(x1, y0);
  c.glVertex2f(x1, y1);
  c.glVertex2f(x0, y1);
  c.glEnd();
}
}  // namespace

TEST(DisplayLists, CompileDoesNotExecuteCompileAndExecuteDoes) {
  Context ctx(test::small_config(4, 4));
  test::window_projection(ctx);
  const GLuint base = ctx.glGenLists(2);
  EXPECT_EQ(base, 1u);
  ctx.glNewList(base, GL_COMPILE);
  ctx.glColor3f(1, 0, 0);
  quad(ctx, 0, 0, 2, 4);
  ctx.glEndList();
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 0u);  // not executed
  EXPECT_EQ(ctx.total_counters().fragments_generated, 0u);
  ctx.glNewList(base + 1, GL_COMPILE_AND_EXECUTE);
  ctx.glColor3f(0, 1, 0);
  quad(ctx, 2, 0, 4, 4);
  ctx.glEndList();
  EXPECT_EQ(pixel(ctx, 3, 0)[1], 255u);
  ctx.glCallList(base);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 255u);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 16u);
  EXPECT_EQ(ctx.glIsList(base), GL_TRUE);
  ctx.glDeleteLists(base, 2);
  EXPECT_EQ(ctx.glIsList(base), GL_FALSE);
  EXPECT_EQ(ctx.glGenLists(3), 1u);  // names are free again
}

TEST(DisplayLists, ErrorsInCompiledCallsAppearAtExecution) {
  Context ctx(test::small_config(4, 4));
  ctx.glNewList(5, GL_COMPILE);
  ctx.glEnable(0x1234);
  ctx.glEndList();
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ctx.glCallList(5);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
}

TEST(DisplayLists, CallListsWithBase) {
  Context ctx(test::small_config(4, 4));
  test::window_projection(ctx);
  ctx.glNewList(10, GL_COMPILE);
  quad(ctx, 0, 0, 1, 1);
  ctx.glEndList();
  ctx.glNewList(12, GL_COMPILE);
  quad(ctx, 3, 3, 4, 4);
  ctx.glEndList();
  ctx.glListBase(10);
  const GLubyte offsets[3] = {0, 2, 1};  // 11 does not exist: ignored
  ctx.glCallLists(3, GL_UNSIGNED_BYTE, offsets);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 2u);
}

TEST(VertexArrays, DrawArraysAndElementsMatchImmediateMode) {
  const float verts[] = {0, 0, 4, 0, 4, 4, 0, 4};
  const GLubyte colors[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  auto immediate = [&](Context& c) {
    c.glBegin(GL_QUADS);
    for (int k = 0; k < 4; ++k) {
      c.glColor4ub(colors[4 * k], colors[4 * k + 1], colors[4 * k + 2], colors[4 * k + 3]);
      c.glVertex2f(verts[2 * k], verts[2 * k + 1]);
    }
    c.glEnd();
  };
  Context a(test::small_config(4, 4)), b(test::small_config(4, 4)), e(test::small_config(4, 4));
  for (Context* c : {&a, &b, &e}) test::window_projection(*c);
  immediate(a);
  for (Context* c : {&b, &e}) {
    c->glEnableClientState(GL_VERTEX_ARRAY);
    c->glEnableClientState(GL_COLOR_ARRAY);
    c->glVertexPointer(2, GL_FLOAT, 0, verts);
    c->glColorPointer(4, GL_UNSIGNED_BYTE, 0, colors);
  }
  b.glDrawArrays(GL_QUADS, 0, 4);
  const GLushort idx[] = {0, 1, 2, 3};
  e.glDrawElements(GL_QUADS, 4, GL_UNSIGNED_SHORT, idx);
  EXPECT_EQ(a.framebuffer().color[0].rgba, b.framebuffer().color[0].rgba);
  EXPECT_EQ(a.framebuffer().color[0].rgba, e.framebuffer().color[0].rgba);
  EXPECT_TRUE(a.total_counters() == b.total_counters());
}

TEST(VertexArrays, CompiledIntoListsWithTheirData) {
  // §5.4: array contents are read when the list is compiled, not when it runs.
  float verts[] = {0, 0, 4, 0, 0, 4};
  Context ctx(test::small_config(4, 4));
  test::window_projection(ctx);
  ctx.glEnableClientState(GL_VERTEX_ARRAY);
  ctx.glVertexPointer(2, GL_FLOAT, 0, verts);
  ctx.glNewList(1, GL_COMPILE);
  ctx.glDrawArrays(GL_TRIANGLES, 0, 3);
  ctx.glEndList();
  verts[2] = 0.5f;  // would make the triangle thin
  ctx.glCallList(1);
  // Triangle (0,0), (4,0), (0,4): centres with x + y <= 2 (x + y = 3 lies on the right/top
  // hypotenuse, excluded): 3 + 2 + 1 = 6.
  EXPECT_EQ(ctx.total_counters().fragments_generated, 6u);
}

TEST(DisplayLists, StateChangedBetweenPrimitivesReachesTheirFragments) {
  // The stage setup of a primitive is worked out once for the primitives that follow until a
  // call that may change state (Context::primitive_stages_setup): changes inside a list, between
  // Begin/End blocks, must still reach the fragments. Texture A red, texture B blue (1x1,
  // REPLACE), then no texture and green: three strips of 70 quads each (enough to be queued to
  // the raster lanes on two threads), each strip its own colour.
  for (int threads : {1, 2}) {
    Context ctx(test::small_config(16, 4));
    ctx.set_threads(threads);
    test::window_projection(ctx);
    GLuint tex[2];
    ctx.glGenTextures(2, tex);
    const GLubyte red[4] = {255, 0, 0, 255}, blue[4] = {0, 0, 255, 255};
    for (int k = 0; k < 2; ++k) {
      ctx.glBindTexture(GL_TEXTURE_2D, tex[k]);
      ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, k == 0 ? red : blue);
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    }
    ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    const GLuint list = ctx.glGenLists(1);
    ctx.glNewList(list, GL_COMPILE);
    ctx.glBindTexture(GL_TEXTURE_2D, tex[0]);
    ctx.glEnable(GL_TEXTURE_2D);
    for (int k = 0; k < 70; ++k) quad(ctx, 0, 0, 8, 4);
    ctx.glBindTexture(GL_TEXTURE_2D, tex[1]);
    for (int k = 0; k < 70; ++k) quad(ctx, 8, 0, 12, 4);
    ctx.glDisable(GL_TEXTURE_2D);
    ctx.glColor3f(0, 1, 0);
    for (int k = 0; k < 70; ++k) quad(ctx, 12, 0, 16, 4);
    ctx.glEndList();
    ctx.glCallList(list);
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 16; ++x) {
        const auto p = pixel(ctx, x, y);
        const unsigned want_r = x < 8 ? 255u : 0u, want_g = x >= 12 ? 255u : 0u, want_b = x >= 8 && x < 12 ? 255u : 0u;
        ASSERT_EQ(p[0], want_r) << threads << " threads, x " << x << " y " << y;
        ASSERT_EQ(p[1], want_g) << threads << " threads, x " << x << " y " << y;
        ASSERT_EQ(p[2], want_b) << threads << " threads, x " << x << " y " << y;
      }
    }
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  }
}
