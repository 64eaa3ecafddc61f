// Line segments (§3.4), polygon modes LINE and POINT (§3.5.4) and point size (§3.3), against
// fragment sets and values derived by hand from the spec (docs/arithmetic.md A30-A34).
//
// Window coordinates here are object coordinates (an orthographic projection onto a window
// whose sides are powers of two: every transformation step is exact), so a vertex at
// (0.5, 0.5) is the centre of pixel (0, 0).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "stages/line_rasterizer.hpp"
#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {

using Pixels = std::set<std::pair<int, int>>;

// Additive blending of 1/255 red per fragment: a pixel's red code counts its fragments.
void count_fragments_mode(Context& ctx) {
  ctx.glEnable(GL_BLEND);
  ctx.glBlendFunc(GL_ONE, GL_ONE);
  ctx.glColor4f(1.0f / 255.0f, 0, 0, 0);
}

// The pixels written, each of which must have been written once.
Pixels written_once(const Context& ctx) {
  Pixels out;
  const auto& c = ctx.config();
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const auto red = pixel(ctx, x, y)[0];
      if (red == 0) continue;
      EXPECT_EQ(red, 1u) << "pixel " << x << "," << y << " written " << red << " times";
      out.insert({x, y});
    }
  return out;
}

void segment(Context& ctx, GLenum mode, std::initializer_list<std::pair<float, float>> vertices) {
  ctx.glBegin(mode);
  for (const auto& [x, y] : vertices) ctx.glVertex2f(x, y);
  ctx.glEnd();
}

// Fragments handed to the stages by rasterize_line, with their data.
struct Captured {
  int x, y;
  std::array<std::uint16_t, 4> rgba;
  std::uint32_t depth;
  double s, fog;
};
struct CaptureSink : FragmentSink {
  std::vector<Captured> fragments;
  void process(FragmentSpan& span) override {
    const auto take = [&](const FragmentSpan& r) {
      for (int i = 0; i < r.count; ++i)
        fragments.push_back(Captured{r.x0 + i, r.y, {r.rgba[4 * i], r.rgba[4 * i + 1], r.rgba[4 * i + 2], r.rgba[4 * i + 3]},
                                     r.depth[i], r.s[i], r.fog[i]});
    };
    if (!span.rows) return take(span);
    for (int k = 0; k < span.row_count; ++k) take(span.row(k));
  }
};

}  // namespace

// §3.4.1's diamond-exit rule by hand for the segment (0.5, 0.5) → (4.5, 2.5), y = 0.5 +
// (x − 0.5)/2. The segment is x-major (slope 1/2); a pixel's diamond |x − xc| + |y − yc| < 1/2
// is met only where the segment crosses the column's centre line x = xc with |y − yc| < 1/2.
//   column 0, x = 0.5: y = 0.5, the centre of (0, 0): pa lies in it, the segment leaves it: (0, 0).
//   column 1, x = 1.5: y = 1.0, on the corner between rows 0 and 1. The perturbed segment,
//     moved by (−ε, −ε²), crosses x = 1.5 at y = 1 + ε/2 − ε²: row 1's diamond, (1, 1).
//   column 2, x = 2.5: y = 1.5, the centre of (2, 1).
//   column 3, x = 3.5: y = 2.0, a corner again: row 2, (3, 2).
//   column 4, x = 4.5: y = 2.5, the centre of (4, 2), which holds pb: no fragment.
// Reversed, (4.5, 2.5) → (0.5, 0.5): (4, 2) holds the start; at x = 3.5 the perturbed segment
// is at y = 2 + ε/2 − ε² (the perturbation does not depend on the direction): (3, 2); then
// (2, 1); at x = 1.5, y = 1 + ε/2 − ε²: (1, 1); (0, 0) holds the end.
TEST(LineRaster, DiamondExitRuleByHand) {
  {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    segment(ctx, GL_LINES, {{0.5f, 0.5f}, {4.5f, 2.5f}});
    EXPECT_EQ(written_once(ctx), (Pixels{{0, 0}, {1, 1}, {2, 1}, {3, 2}}));
    EXPECT_EQ(ctx.total_counters().fragments_generated, 4u);
    EXPECT_EQ(ctx.total_counters().primitives_in, 1u);
  }
  {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    segment(ctx, GL_LINES, {{4.5f, 2.5f}, {0.5f, 0.5f}});
    EXPECT_EQ(written_once(ctx), (Pixels{{4, 2}, {3, 2}, {2, 1}, {1, 1}}));
  }
}

// A segment along a pixel boundary: the perturbation (−ε, −ε²) moves a horizontal one below
// (y = 2 − ε² is in row 1's diamonds) and a vertical one to the left (x = 3 − ε, column 2).
TEST(LineRaster, SegmentsOnPixelBoundariesGoBelowAndLeft) {
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  count_fragments_mode(ctx);
  segment(ctx, GL_LINES, {{0.5f, 2.0f}, {4.5f, 2.0f}});  // columns 0-3 (4 holds the end)
  segment(ctx, GL_LINES, {{3.0f, 3.5f}, {3.0f, 6.5f}});  // rows 3-5
  EXPECT_EQ(written_once(ctx), (Pixels{{0, 1}, {1, 1}, {2, 1}, {3, 1}, {2, 3}, {2, 4}, {2, 5}}));
}

// A strip's segments share their joint: the first leaves out the pixel holding its end, the
// second starts there, so every pixel is written once. The loop's closing segment
// (0.5, 4.5) → (0.5, 0.5) gives column 0's rows 4 down to 1; the square's outline of 16
// pixels is complete, each once. Without the closing segment (a strip) 12.
TEST(LineRaster, StripJointsOnceAndLoopCloses) {
  const std::initializer_list<std::pair<float, float>> square = {{0.5f, 0.5f}, {4.5f, 0.5f}, {4.5f, 4.5f}, {0.5f, 4.5f}};
  Pixels outline;
  for (int i = 0; i < 4; ++i) outline.insert({i, 0}), outline.insert({4, i}), outline.insert({4 - i, 4}), outline.insert({0, 4 - i});
  ASSERT_EQ(outline.size(), 16u);
  {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    segment(ctx, GL_LINE_LOOP, square);
    EXPECT_EQ(written_once(ctx), outline);
    EXPECT_EQ(ctx.total_counters().primitives_in, 4u);
    EXPECT_EQ(ctx.total_counters().fragments_generated, 16u);
  }
  {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    segment(ctx, GL_LINE_STRIP, square);
    Pixels open = outline;
    for (int row = 1; row <= 3; ++row) open.erase({0, row});
    open.erase({0, 4});  // the strip's last segment stops before its end (0.5, 4.5)
    EXPECT_EQ(written_once(ctx), open);
    EXPECT_EQ(ctx.total_counters().primitives_in, 3u);
  }
}

// glDrawArrays assembles the same segments: the loop's outline of 16 pixels (as above).
TEST(LineRaster, DrawArraysLoopClosesToo) {
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  count_fragments_mode(ctx);
  const GLfloat square[] = {0.5f, 0.5f, 4.5f, 0.5f, 4.5f, 4.5f, 0.5f, 4.5f};
  ctx.glEnableClientState(GL_VERTEX_ARRAY);
  ctx.glVertexPointer(2, GL_FLOAT, 0, square);
  ctx.glDrawArrays(GL_LINE_LOOP, 0, 4);
  EXPECT_EQ(written_once(ctx).size(), 16u);
  EXPECT_EQ(ctx.total_counters().primitives_in, 4u);
}

// (0.5, 0.5) → (4.5, 0.5), red 0 → 1: fragment i at t = i/4 (eq. 3.5, w = 1 so eq. 3.6 is
// linear): codes round(255·i/4) = 0, 64 (63.75), 128 (127.5, ties up, A1), 191 (191.25).
// Flat (§2.13.7): the segment's second vertex, 255 everywhere.
TEST(LineRaster, SmoothAndFlatColour) {
  for (bool flat : {false, true}) {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    if (flat) ctx.glShadeModel(GL_FLAT);
    ctx.glBegin(GL_LINES);
    ctx.glColor3f(0, 0, 0);
    ctx.glVertex2f(0.5f, 0.5f);
    ctx.glColor3f(1, 0, 0);
    ctx.glVertex2f(4.5f, 0.5f);
    ctx.glEnd();
    const std::uint32_t smooth[] = {0, 64, 128, 191};
    for (int i = 0; i < 4; ++i) EXPECT_EQ(pixel(ctx, i, 0)[0], flat ? 255u : smooth[i]) << i << (flat ? " flat" : " smooth");
    EXPECT_EQ(pixel(ctx, 4, 0)[0], 0u);
  }
}

// Eq. 3.6 with w_a = 1, w_b = 3 on (0.5, 0.5) → (8.5, 0.5): at column 4, t = 1/2 and the
// weights (1 − t)/w_a = 1/2, t/w_b = 1/6, so the perspective-correct parameter is
// (1/6)/(2/3) = 1/4: s from 0 to 1 gives 1/4, red from 0 to 1 gives code round(63.75) = 64,
// eye z from −1 to −3 gives −1.5 (fog coordinate 1.5). Depth is linear in t (eq. 3.7):
// z from 0 to 1 gives 1/2, code round(0.5·(2^24 − 1)) = 8388608.
TEST(LineRaster, PerspectiveCorrectAttributesAndLinearDepth) {
  RasterVertex a, b;
  a.x = 0.5, a.y = 0.5, a.z = 0.0, a.w = 1.0, a.color = Vec4(0, 0, 0, 1), a.tex = Vec4(0, 0, 0, 1), a.eye_z = -1.0;
  b.x = 8.5, b.y = 0.5, b.z = 1.0, b.w = 3.0, b.color = Vec4(1, 0, 0, 1), b.tex = Vec4(1, 0, 0, 1), b.eye_z = -3.0;
  TriangleOptions o;
  o.texcoords = true;
  o.texcoords_used = 1;
  o.fog = true;
  RasterTarget target;
  target.width = target.height = 16;
  SpanBuffers buffers(16);
  CaptureSink sink;
  Counters counters;
  rasterize_line(a, b, o, LineOptions{}, target, buffers, sink, counters);
  ASSERT_EQ(sink.fragments.size(), 8u);
  const Captured& f = sink.fragments[4];
  EXPECT_EQ(f.x, 4);
  EXPECT_EQ(f.y, 0);
  EXPECT_DOUBLE_EQ(f.s, 0.25);
  EXPECT_DOUBLE_EQ(f.fog, 1.5);
  EXPECT_EQ(f.rgba[0], 64u);
  EXPECT_EQ(f.depth, 8388608u);
  EXPECT_EQ(counters.fragments_generated, 8u);
  // The first fragment is the start's (t = 0): its attributes exactly.
  EXPECT_EQ(sink.fragments[0].x, 0);
  EXPECT_DOUBLE_EQ(sink.fragments[0].s, 0.0);
  EXPECT_EQ(sink.fragments[0].depth, 0u);
}

// §3.4.2: bit ⌊s/factor⌋ mod 16 of the pattern, s counting the fragments from the start.
TEST(LineStipple, PatternFactorAndCounterResets) {
  const auto drawn = [](GLint factor, GLushort pattern, GLenum mode, std::initializer_list<std::pair<float, float>> v) {
    Context ctx(test::small_config(32, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    ctx.glEnable(GL_LINE_STIPPLE);
    ctx.glLineStipple(factor, pattern);
    segment(ctx, mode, v);
    return written_once(ctx);
  };
  const auto columns = [](std::initializer_list<int> cs) {
    Pixels p;
    for (int c : cs) p.insert({c, 0});
    return p;
  };
  // 16 fragments, columns 0-15: 0x00FF keeps the first 8.
  EXPECT_EQ(drawn(1, 0x00FF, GL_LINES, {{0.5f, 0.5f}, {16.5f, 0.5f}}), columns({0, 1, 2, 3, 4, 5, 6, 7}));
  // Factor 2, bits 0 and 2: s = 0, 1 (bit 0) and s = 4, 5 (bit 2).
  EXPECT_EQ(drawn(2, 0x0005, GL_LINES, {{0.5f, 0.5f}, {16.5f, 0.5f}}), columns({0, 1, 4, 5}));
  // The pattern repeats every 16 fragments: 0x0001 on 20 fragments keeps s = 0 and 16.
  EXPECT_EQ(drawn(1, 0x0001, GL_LINES, {{0.5f, 0.5f}, {20.5f, 0.5f}}), columns({0, 16}));
  // A strip carries s on: its second segment's fragments are s = 4-7, bits 4-7 of 0x00F0.
  EXPECT_EQ(drawn(1, 0x00F0, GL_LINE_STRIP, {{0.5f, 0.5f}, {4.5f, 0.5f}, {8.5f, 0.5f}}), columns({4, 5, 6, 7}));
  // Separate segments reset s: both are s = 0-3, no bit of 0x00F0.
  EXPECT_EQ(drawn(1, 0x00F0, GL_LINES, {{0.5f, 0.5f}, {4.5f, 0.5f}, {4.5f, 0.5f}, {8.5f, 0.5f}}), Pixels{});
  // Begin resets it too: two strips of one segment each.
  {
    Context ctx(test::small_config(32, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    ctx.glEnable(GL_LINE_STIPPLE);
    ctx.glLineStipple(1, 0x000F);
    segment(ctx, GL_LINE_STRIP, {{0.5f, 0.5f}, {4.5f, 0.5f}});
    segment(ctx, GL_LINE_STRIP, {{4.5f, 0.5f}, {8.5f, 0.5f}});
    EXPECT_EQ(written_once(ctx), columns({0, 1, 2, 3, 4, 5, 6, 7}));
  }
  // The state reads back (Table 6.11).
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  ctx.glLineStipple(300, 0xABCD);
  double v[4] = {};
  ctx.glGetDoublev(GL_LINE_STIPPLE_REPEAT, v);
  EXPECT_EQ(v[0], 256.0);  // clamped to [1, 256]
  ctx.glGetDoublev(GL_LINE_STIPPLE_PATTERN, v);
  EXPECT_EQ(v[0], 43981.0);
  EXPECT_FALSE(ctx.glIsEnabled(GL_LINE_STIPPLE));
}

// §3.4.2: the segment moved by −(w − 1)/2 across its major direction is rasterized with width
// one, and each of its fragments becomes a column (x-major) or row (y-major) of w.
//   width 3 on y = 2.5: the width-one segment on y = 1.5, rows 1-3 in columns 0-5.
//   width 2 on y = 2.5: on y = 2.0, a boundary, rows 1 (the perturbation goes below) and 2.
//   width 3 on x = 2.5 (y-major): on x = 1.5, columns 1-3 in rows 0-5.
TEST(LineRaster, WideLinesAreColumnsOfWidthFragments) {
  const auto block = [](int x0, int x1, int y0, int y1) {
    Pixels p;
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y) p.insert({x, y});
    return p;
  };
  const struct {
    float width;
    std::pair<float, float> a, b;
    Pixels expected;
  } cases[] = {{3.0f, {0.5f, 2.5f}, {6.5f, 2.5f}, block(0, 5, 1, 3)},
               {2.0f, {0.5f, 2.5f}, {6.5f, 2.5f}, block(0, 5, 1, 2)},
               {2.6f, {0.5f, 2.5f}, {6.5f, 2.5f}, block(0, 5, 1, 3)},  // rounds to 3
               {3.0f, {2.5f, 0.5f}, {2.5f, 6.5f}, block(1, 3, 0, 5)}};
  for (const auto& c : cases) {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    ctx.glLineWidth(c.width);
    segment(ctx, GL_LINES, {c.a, c.b});
    EXPECT_EQ(written_once(ctx), c.expected) << c.width;
    EXPECT_EQ(ctx.total_counters().fragments_generated, c.expected.size());
  }
}

// §2.11: a segment crossing the view volume's edge is cut there. (2.5, 2.5) → (12.5, 2.5) on
// an 8-wide window is cut at x = 8; the cut end lies on the boundary of column 7's diamond,
// which A31 does not except (the uncut segment leaves that diamond): columns 2-7.
// With a viewport of the window's left half, (0.5, 2.5) → (7.5, 2.5) in its coordinates
// ends at x = 4: columns 0-3 only, the window's columns 4-7 stay empty.
TEST(LineClipping, CrossingTheViewportEdgeIsCut) {
  {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    segment(ctx, GL_LINES, {{2.5f, 2.5f}, {12.5f, 2.5f}});
    EXPECT_EQ(written_once(ctx), (Pixels{{2, 2}, {3, 2}, {4, 2}, {5, 2}, {6, 2}, {7, 2}}));
    EXPECT_EQ(ctx.total_counters().primitives_clipped, 1u);
    segment(ctx, GL_LINES, {{9.5f, 2.5f}, {12.5f, 5.5f}});  // wholly outside
    EXPECT_EQ(ctx.total_counters().primitives_clipped_out, 1u);
  }
  {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    ctx.glViewport(0, 0, 4, 8);
    ctx.glMatrixMode(GL_PROJECTION);
    ctx.glLoadIdentity();
    ctx.glOrtho(0, 4, 0, 8, -1, 1);
    ctx.glMatrixMode(GL_MODELVIEW);
    count_fragments_mode(ctx);
    segment(ctx, GL_LINES, {{0.5f, 2.5f}, {7.5f, 2.5f}});
    EXPECT_EQ(written_once(ctx), (Pixels{{0, 2}, {1, 2}, {2, 2}, {3, 2}}));
  }
  {
    // A user clip plane x <= 3 (−x + 3 >= 0) cuts (0.5, 1.5) → (6.5, 1.5) at x = 3: columns 0-2.
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    const GLdouble plane[4] = {-1, 0, 0, 3};
    ctx.glClipPlane(GL_CLIP_PLANE0, plane);
    ctx.glEnable(GL_CLIP_PLANE0);
    count_fragments_mode(ctx);
    segment(ctx, GL_LINES, {{0.5f, 1.5f}, {6.5f, 1.5f}});
    EXPECT_EQ(written_once(ctx), (Pixels{{0, 1}, {1, 1}, {2, 1}}));
  }
}

// §3.5.4 on the triangle (0.5, 0.5), (6.5, 0.5), (0.5, 6.5) (counter-clockwise, front):
//   edge 0 → 1, y = 0.5: columns 0-5 of row 0 (column 6 holds its end);
//   edge 1 → 2, x + y = 7 from (6.5, 0.5): (6, 0), (5, 1), (4, 2), (3, 3), (2, 4), (1, 5), the
//     centres on it ((0, 6) holds its end; the corners it passes are the corners of diamonds,
//     outside them);
//   edge 2 → 0, x = 0.5 downwards: rows 6-1 of column 0.
// 18 pixels, each once; with vertex 1's edge flag false, edge 1 → 2 is not drawn: 12. In
// mode POINT, the vertices that start a boundary edge: (0, 0), (0, 6) (and (6, 0) with the flag).
TEST(PolygonMode, LineAndPointHonourEdgeFlags) {
  Pixels edge01, edge12, edge20;
  for (int i = 0; i <= 5; ++i) edge01.insert({i, 0});
  for (int i = 0; i <= 5; ++i) edge12.insert({6 - i, i});
  for (int i = 1; i <= 6; ++i) edge20.insert({0, i});
  const auto draw = [](GLenum mode, bool flag1, GLenum primitive) {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    ctx.glPolygonMode(GL_FRONT_AND_BACK, mode);
    count_fragments_mode(ctx);
    ctx.glBegin(primitive);
    ctx.glVertex2f(0.5f, 0.5f);
    ctx.glEdgeFlag(flag1 ? GL_TRUE : GL_FALSE);
    ctx.glVertex2f(6.5f, 0.5f);
    ctx.glEdgeFlag(GL_TRUE);
    ctx.glVertex2f(0.5f, 6.5f);
    ctx.glEnd();
    return written_once(ctx);
  };
  Pixels all = edge01;
  all.insert(edge12.begin(), edge12.end());
  all.insert(edge20.begin(), edge20.end());
  ASSERT_EQ(all.size(), 18u);
  Pixels without12 = edge01;
  without12.insert(edge20.begin(), edge20.end());
  EXPECT_EQ(draw(GL_LINE, true, GL_TRIANGLES), all);
  EXPECT_EQ(draw(GL_LINE, false, GL_TRIANGLES), without12);
  // §2.6.2: a strip's edges are all boundary edges, whatever the flags.
  EXPECT_EQ(draw(GL_LINE, false, GL_TRIANGLE_STRIP), all);
  EXPECT_EQ(draw(GL_POINT, true, GL_TRIANGLES), (Pixels{{0, 0}, {6, 0}, {0, 6}}));
  EXPECT_EQ(draw(GL_POINT, false, GL_TRIANGLES), (Pixels{{0, 0}, {0, 6}}));
}

// §3.5.5 for polygons drawn as lines: the offset of the polygon's plane, added to every
// fragment's depth when POLYGON_OFFSET_LINE is on (and only then). A flat triangle at window
// z = 1/2 (object z = 0) with units 4: depth code 2^23 + 4 at 24 bits (m = 0).
TEST(PolygonMode, OffsetLineAndPoint) {
  for (GLenum mode : {GL_LINE, GL_POINT}) {
    for (bool on : {false, true}) {
      Context ctx(test::small_config(8, 8));
      test::window_projection(ctx);
      ctx.glPolygonMode(GL_FRONT_AND_BACK, mode);
      ctx.glPolygonOffset(0.0f, 4.0f);
      ctx.glEnable(GL_DEPTH_TEST);
      ctx.glDepthFunc(GL_ALWAYS);
      if (on) ctx.glEnable(mode == GL_LINE ? GL_POLYGON_OFFSET_LINE : GL_POLYGON_OFFSET_POINT);
      ctx.glEnable(GL_POLYGON_OFFSET_FILL);  // no effect on lines and points
      segment(ctx, GL_TRIANGLES, {{0.5f, 0.5f}, {6.5f, 0.5f}, {0.5f, 6.5f}});
      const Framebuffer& fb = ctx.framebuffer();
      // Window z = 0.5 is code round(0.5·(2^24 − 1)) = 8388608; one unit is one code.
      EXPECT_EQ(fb.depth[fb.pixel_index(0, 0)], on ? 8388612u : 8388608u) << (mode == GL_LINE ? "line" : "point");
    }
  }
}

// §3.3: a point of size s is a square of w = round(s) fragments; odd w centred on the pixel
// holding the point, even w on the nearest pixel corner. (3.5, 3.5) size 3: columns and
// rows 2-4; (3.2, 3.7) size 2: the nearest corner (3, 4), columns 2-3, rows 3-4.
TEST(PointSize, SquaresOfRoundedWidth) {
  const auto draw = [](float size, float x, float y) {
    Context ctx(test::small_config(8, 8));
    test::window_projection(ctx);
    count_fragments_mode(ctx);
    ctx.glPointSize(size);
    segment(ctx, GL_POINTS, {{x, y}});
    return written_once(ctx);
  };
  Pixels three, two;
  for (int x = 2; x <= 4; ++x)
    for (int y = 2; y <= 4; ++y) three.insert({x, y});
  for (int x = 2; x <= 3; ++x)
    for (int y = 3; y <= 4; ++y) two.insert({x, y});
  EXPECT_EQ(draw(3.0f, 3.5f, 3.5f), three);
  EXPECT_EQ(draw(2.0f, 3.2f, 3.7f), two);
  EXPECT_EQ(draw(0.2f, 3.5f, 3.5f), (Pixels{{3, 3}}));  // at least one
}

// Lines through the raster lanes: the same bits and counters on 1 and 3 threads.
TEST(LineRaster, SameOnAnyNumberOfThreads) {
  const auto draw = [](Context& ctx) {
    test::window_projection(ctx);
    ctx.glEnable(GL_DEPTH_TEST);
    ctx.glEnable(GL_LINE_STIPPLE);
    ctx.glLineStipple(2, 0x3F5B);
    unsigned seed = 7;
    const auto next = [&] { return (seed = seed * 1103515245u + 12345u) >> 8 & 0xFFFF; };
    for (int k = 0; k < 300; ++k) {
      ctx.glLineWidth(static_cast<float>(1 + next() % 4));
      ctx.glBegin(k % 3 == 0 ? GL_LINES : k % 3 == 1 ? GL_LINE_STRIP : GL_LINE_LOOP);
      for (int v = 0; v < 4; ++v) {
        ctx.glColor3f(static_cast<float>(next() % 256) / 255.0f, static_cast<float>(next() % 256) / 255.0f, 0.5f);
        ctx.glVertex3f(static_cast<float>(next() % 1400) / 10.0f - 2.0f, static_cast<float>(next() % 1100) / 10.0f - 2.0f,
                       static_cast<float>(next() % 200) / 100.0f - 1.0f);
      }
      ctx.glEnd();
    }
  };
  Context one(test::small_config(128, 100));
  draw(one);
  Context many(test::small_config(128, 100));
  many.set_threads(3);
  draw(many);
  EXPECT_EQ(one.framebuffer().color[0].rgba, many.framebuffer().color[0].rgba);
  EXPECT_EQ(one.framebuffer().depth, many.framebuffer().depth);
  EXPECT_TRUE(one.total_counters() == many.total_counters());
  EXPECT_GT(one.total_counters().fragments_generated, 1000u);
}
