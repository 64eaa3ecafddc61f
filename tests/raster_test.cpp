// Rasterization: the edge rule, attribute interpolation, depth quantisation and
// polygon offset, against values computed by hand.
#include <gtest/gtest.h>

#include <initializer_list>
#include <random>
#include <string>

#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {

// Additive blending of 1/255 per fragment: each pixel's red code counts its fragments.
void count_fragments_mode(Context& ctx) {
  ctx.glEnable(GL_BLEND);
  ctx.glBlendFunc(GL_ONE, GL_ONE);
  ctx.glColor4f(1.0f / 255.0f, 0, 0, 0);
}

void expect_every_pixel_once(const Context& ctx) {
  const auto& c = ctx.config();
  int wrong = 0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x)
      if (pixel(ctx, x, y)[0] != 1u && ++wrong < 5) ADD_FAILURE() << "pixel " << x << "," << y << " written " << pixel(ctx, x, y)[0] << " times";
  EXPECT_EQ(wrong, 0);
}

}  // namespace

TEST(EdgeRule, FanTilingTheViewportWritesEveryPixelOnce) {
  Context ctx(test::small_config(37, 29));
  test::window_projection(ctx);
  count_fragments_mode(ctx);
  // A fan around an off-grid centre whose rim runs along the window border and through
  // pixel centres and corners, so that many centres lie exactly on shared edges.
  ctx.glBegin(GL_TRIANGLE_FAN);
  ctx.glVertex2f(17.5f, 13.5f);
  const float rim[][2] = {{0, 0}, {9.5f, 0}, {20, 0}, {37, 0}, {37, 14.5f}, {37, 29}, {18.5f, 29}, {0, 29}, {0, 12}, {0, 0}};
  for (const auto& v : rim) ctx.glVertex2f(v[0], v[1]);
  ctx.glEnd();
  expect_every_pixel_once(ctx);
  EXPECT_EQ(ctx.total_counters().fragments_generated, 37u * 29u);
}

TEST(EdgeRule, JitteredMeshWritesEveryPixelOnce) {
  // A grid of quads split into triangles, interior vertices jittered by up to 0.45 px with
  // positions on the 1/16 sub-pixel grid, both diagonals: every centre covered exactly once.
  const int W = 48, H = 40, N = 6;
  Context ctx(test::small_config(W, H));
  test::window_projection(ctx);
  count_fragments_mode(ctx);
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> jitter(-7, 7);
  float vx[N + 1][N + 1], vy[N + 1][N + 1];
  for (int j = 0; j <= N; ++j)
    for (int i = 0; i <= N; ++i) {
      vx[j][i] = static_cast<float>(W * i) / N + ((i > 0 && i < N) ? jitter(rng) / 16.0f : 0.0f);
      vy[j][i] = static_cast<float>(H * j) / N + ((j > 0 && j < N) ? jitter(rng) / 16.0f : 0.0f);
    }
  ctx.glBegin(GL_TRIANGLES);
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      auto v = [&](int a, int b) { ctx.glVertex2f(vx[j + b][i + a], vy[j + b][i + a]); };
      if ((i + j) % 2) {
        v(0, 0); v(1, 0); v(1, 1);
        v(0, 0); v(1, 1); v(0, 1);
      } else {
        v(0, 0); v(1, 0); v(0, 1);
        v(1, 0); v(1, 1); v(0, 1);
      }
    }
  ctx.glEnd();
  expect_every_pixel_once(ctx);
}

TEST(EdgeRule, CentreOnEdgesLeftBottomInRightTopOut) {
  // Square [1,3] x [1,3] as two triangles: centres 1.5 and 2.5 are inside; a square
  // [0.5, 2.5] has centres exactly on its left/bottom (inside) and right/top (outside) edges.
  Context ctx(test::small_config(4, 4));
  test::window_projection(ctx);
  count_fragments_mode(ctx);
  ctx.glBegin(GL_QUADS);
  ctx.glVertex2f(0.5f, 0.5f);
  ctx.glVertex2f(2.5f, 0.5f);
  ctx.glVertex2f(2.5f, 2.5f);
  ctx.glVertex2f(0.5f, 2.5f);
  ctx.glEnd();
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(pixel(ctx, x, y)[0], (x <= 1 && y <= 1) ? 1u : 0u) << x << "," << y;
}

TEST(Interpolation, ScreenLinearWhenWIsOne) {
  for (int bits : {8, 12}) {
    Context ctx(test::small_config(8, 8, bits));
    test::window_projection(ctx);
    ctx.glBegin(GL_TRIANGLES);
    ctx.glColor3f(1, 0, 0);
    ctx.glVertex2f(0, 0);
    ctx.glColor3f(0, 1, 0);
    ctx.glVertex2f(8, 0);
    ctx.glColor3f(0, 0, 1);
    ctx.glVertex2f(0, 8);
    ctx.glEnd();
    // Centre (1.5, 1.5): weights 5/8 (red), 3/16 (green), 3/16 (blue).
    const double m = (1 << bits) - 1;
    const auto p = pixel(ctx, 1, 1);
    EXPECT_EQ(p[0], static_cast<std::uint32_t>(std::floor(5.0 / 8.0 * m + 0.5)));  // 159 / 2559
    EXPECT_EQ(p[1], static_cast<std::uint32_t>(std::floor(3.0 / 16.0 * m + 0.5)));  // 48 / 768
    EXPECT_EQ(p[2], p[1]);
    EXPECT_EQ(p[3], static_cast<std::uint32_t>(m));
  }
}

TEST(Interpolation, PerspectiveCorrectColour) {
  // Clip coordinates with w = 1, 2, 4 at window (0,0), (8,0), (0,8); identity matrices.
  // At centre (1.5, 1.5) the screen weights 5/8, 3/16, 3/16 become, divided by w,
  // 40/64, 6/64, 3/64: colours 40/49, 6/49, 3/49 (eq. 3.4).
  Context c8(test::small_config(8, 8, 8));
  Context c12(test::small_config(8, 8, 12));
  for (Context* ctx : {&c8, &c12}) {
    ctx->glBegin(GL_TRIANGLES);
    ctx->glColor3f(1, 0, 0);
    ctx->glVertex4f(-1, -1, 0, 1);
    ctx->glColor3f(0, 1, 0);
    ctx->glVertex4f(2, -2, 0, 2);
    ctx->glColor3f(0, 0, 1);
    ctx->glVertex4f(-4, 4, 0, 4);
    ctx->glEnd();
  }
  const auto p8 = pixel(c8, 1, 1);
  EXPECT_EQ(p8[0], 208u);  // 40/49·255 = 208.16
  EXPECT_EQ(p8[1], 31u);   // 6/49·255 = 31.22
  EXPECT_EQ(p8[2], 16u);   // 3/49·255 = 15.61
  const auto p12 = pixel(c12, 1, 1);
  EXPECT_EQ(p12[0], 3343u);  // 40/49·4095 = 3342.86
  EXPECT_EQ(p12[1], 501u);   // 6/49·4095 = 501.43
  EXPECT_EQ(p12[2], 251u);   // 3/49·4095 = 250.71
}

TEST(Depth, QuantisedToThePlaneWidth) {
  for (int depth_bits : {16, 24, 32}) {
    FramebufferConfig cfg = test::small_config(4, 4);
    cfg.depth_bits = depth_bits;
    Context ctx(cfg);
    test::window_projection(ctx);
    ctx.glEnable(GL_DEPTH_TEST);
    ctx.glDepthFunc(GL_ALWAYS);
    ctx.glBegin(GL_QUADS);  // object z 0.2 -> window z 0.4; z = -0.6 -> 0.8
    ctx.glVertex3f(0, 0, 0.2f);
    ctx.glVertex3f(4, 0, 0.2f);
    ctx.glVertex3f(4, 4, 0.2f);
    ctx.glVertex3f(0, 4, 0.2f);
    ctx.glEnd();
    const double m = static_cast<double>((std::uint64_t{1} << depth_bits) - 1);
    // window z = (1 - float(0.2)) / 2 computed as the pipeline does (eq. 2.14): 0.5·(-zo) + 0.5
    const double zw = -static_cast<double>(0.2f) * 0.5 + 0.5;
    EXPECT_EQ(ctx.framebuffer().depth[5], static_cast<std::uint32_t>(std::floor(zw * m + 0.5))) << depth_bits;
  }
  // By hand: 16 bits, window z 0.5 -> 32767.5 -> 32768; 24 bits -> 8388608.
  Context ctx(test::small_config(2, 2));
  test::window_projection(ctx);
  ctx.glClear(GL_DEPTH_BUFFER_BIT);  // to 1.0: LESS passes
  ctx.glEnable(GL_DEPTH_TEST);
  ctx.glBegin(GL_TRIANGLES);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(4, 0);
  ctx.glVertex2f(0, 4);
  ctx.glEnd();
  EXPECT_EQ(ctx.framebuffer().depth[0], 8388608u);
}

TEST(Depth, EveryFunction) {
  // Stored 0.5 (code 8388608 at 24 bits); incoming 0.25, 0.5, 0.75 per column.
  struct Case { GLenum func; bool less, equal, greater; };
  const Case cases[] = {{GL_NEVER, false, false, false}, {GL_LESS, true, false, false},
                        {GL_EQUAL, false, true, false}, {GL_LEQUAL, true, true, false},
                        {GL_GREATER, false, false, true}, {GL_NOTEQUAL, true, false, true},
                        {GL_GEQUAL, false, true, true}, {GL_ALWAYS, true, true, true}};
  for (const Case& c : cases) {
    Context ctx(test::small_config(3, 1));
    test::window_projection(ctx);
    ctx.glClearDepth(0.5);
    ctx.glClear(GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT);
    ctx.glEnable(GL_DEPTH_TEST);
    ctx.glDepthFunc(c.func);
    ctx.glColor3f(1, 1, 1);
    const float z[3] = {0.5f, 0.0f, -0.5f};  // window 0.25, 0.5, 0.75
    for (int i = 0; i < 3; ++i) {
      ctx.glBegin(GL_QUADS);
      ctx.glVertex3f(i, 0, z[i]);
      ctx.glVertex3f(i + 1, 0, z[i]);
      ctx.glVertex3f(i + 1, 1, z[i]);
      ctx.glVertex3f(i, 1, z[i]);
      ctx.glEnd();
    }
    EXPECT_EQ(pixel(ctx, 0, 0)[0], c.less ? 255u : 0u) << enum_name(c.func);
    EXPECT_EQ(pixel(ctx, 1, 0)[0], c.equal ? 255u : 0u) << enum_name(c.func);
    EXPECT_EQ(pixel(ctx, 2, 0)[0], c.greater ? 255u : 0u) << enum_name(c.func);
    const Counters t = ctx.total_counters();
    EXPECT_EQ(t.killed_depth, 3u - (c.less + c.equal + c.greater));
  }
}

TEST(PolygonOffset, UnitsMoveByWholeDepthSteps) {
  // A flat quad at window z 0.5 (slope 0): offset = r·units with r = 1/(2^24 - 1).
  Context ctx(test::small_config(2, 2));
  test::window_projection(ctx);
  ctx.glEnable(GL_DEPTH_TEST);
  ctx.glDepthFunc(GL_ALWAYS);
  ctx.glEnable(GL_POLYGON_OFFSET_FILL);
  ctx.glPolygonOffset(0, -3);
  ctx.glBegin(GL_QUADS);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(2, 0);
  ctx.glVertex2f(2, 2);
  ctx.glVertex2f(0, 2);
  ctx.glEnd();
  // 0.5·(2^24-1) = 8388607.5; minus 3 steps = 8388604.5 -> 8388605 (ties up).
  EXPECT_EQ(ctx.framebuffer().depth[0], 8388605u);
}

TEST(Clipping, TriangleCrossingTheWindowEdgeIsCutNotLost) {
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  ctx.glColor3f(1, 1, 1);
  ctx.glBegin(GL_TRIANGLES);  // half of it lies left of x = 0
  ctx.glVertex2f(-8, 0);
  ctx.glVertex2f(8, 0);
  ctx.glVertex2f(-8, 8);
  ctx.glEnd();
  const Counters t = ctx.total_counters();
  EXPECT_EQ(t.primitives_clipped, 1u);
  // Visible part: x in [0,8], y <= (8 - x)/2 ... centres (x+.5, y+.5) with y+.5 < (8-(x+.5))/2.
  std::uint64_t expected = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const double cx = x + 0.5, cy = y + 0.5;
      if (cy < (8.0 - cx) / 2.0) ++expected;  // no centre lies exactly on the hypotenuse here
    }
  EXPECT_EQ(t.fragments_generated, expected);
}

TEST(Culling, BackFacesCulledAndCounted) {
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  ctx.glEnable(GL_CULL_FACE);
  ctx.glBegin(GL_TRIANGLES);
  ctx.glVertex2f(0, 0);  // clockwise: back-facing
  ctx.glVertex2f(0, 8);
  ctx.glVertex2f(8, 0);
  ctx.glVertex2f(0, 0);  // counter-clockwise: front-facing
  ctx.glVertex2f(8, 0);
  ctx.glVertex2f(0, 8);
  ctx.glEnd();
  EXPECT_EQ(ctx.total_counters().primitives_culled, 1u);
  EXPECT_EQ(ctx.total_counters().primitives_in, 2u);
  // Centres (x+.5, y+.5) inside x + y < 7; those with x + y = 7 lie on the hypotenuse, a
  // right/top edge, so they are out: x + y <= 6 gives 7+6+...+1 = 28.
  EXPECT_EQ(ctx.total_counters().fragments_generated, 28u);
}

TEST(BadInput, NaNAndInfiniteVerticesDropTheirPrimitive) {
  Context ctx(test::small_config(8, 8));
  test::window_projection(ctx);
  ctx.glBegin(GL_TRIANGLES);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(std::nanf(""), 0);
  ctx.glVertex2f(0, 8);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(INFINITY, 0);
  ctx.glVertex2f(0, 8);
  ctx.glEnd();
  ctx.glBegin(GL_POINTS);
  ctx.glVertex4f(1, 1, 0, std::nanf(""));
  ctx.glEnd();
  const Counters t = ctx.total_counters();
  EXPECT_EQ(t.primitives_in, 3u);
  EXPECT_EQ(t.primitives_clipped_out, 3u);
  EXPECT_EQ(t.fragments_generated, 0u);
  EXPECT_FALSE(ctx.warnings().empty());
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(BadInput, HugeViewportIsClampedAndFarAwayGeometryIsHarmless) {
  Context ctx(test::small_config(8, 8));
  ctx.glViewport(-2000000000, -2000000000, 1 << 30, 1 << 30);  // clamped to 4096 x 4096
  GLint vp[4];
  ctx.glGetIntegerv(GL_VIEWPORT, vp);
  EXPECT_EQ(vp[2], 4096);
  ctx.glBegin(GL_TRIANGLES);
  ctx.glVertex2f(-1, -1);
  ctx.glVertex2f(1, -1);
  ctx.glVertex2f(-1, 1);
  ctx.glEnd();
  EXPECT_EQ(ctx.total_counters().fragments_generated, 0u);
}

// Found by fuzzing: a clip w below the smallest normal double has an infinite reciprocal. A
// vertex (-w, -w, 0, w) with w = 1e-310 is the NDC corner (-1, -1) as (-1, -1, 0, 1) is, and
// must draw the same triangle.
TEST(Raster, SubnormalClipWPlacesTheVertexLikeItsNormalisedForm) {
  auto draw = [](double w) {
    Context ctx(test::small_config(16, 16));
    ctx.glColor3f(1, 1, 1);
    ctx.glBegin(GL_TRIANGLES);
    ctx.glVertex4d(-w, -w, 0, w);
    ctx.glVertex4d(1, -1, 0, 1);
    ctx.glVertex4d(0, 1, 0, 1);
    ctx.glEnd();
    return ctx.framebuffer().color[0].rgba;
  };
  const auto normal = draw(1.0), tiny = draw(1e-310);
  EXPECT_EQ(tiny, normal);
  // The triangle covers the window's bottom corners' half: pixel (1, 0) is inside, (0, 15) not.
  EXPECT_EQ(normal[4 * 1], 255u);
  EXPECT_EQ(normal[4 * (15 * 16)], 0u);
}

// The guard band of snapping: window coordinates are snapped to 1/2^b pixel in doubled units
// (A5), and clamped to ±2^17 first (found by fuzzing: the clipper's rounding on degenerate
// input produced −2.5e30, past 64 bits once snapped).
TEST(Raster, SnappingHasAGuardBand) {
  EXPECT_EQ(snap_coordinate(3.5, 4), 112);           // 3.5 · 16 = 56, doubled
  EXPECT_EQ(snap_coordinate(-1.03125, 4), -32);      // −16.5 rounds half up to −16
  EXPECT_EQ(snap_coordinate(131072.0, 12), std::int64_t{1} << 30);
  EXPECT_EQ(snap_coordinate(-2.5e30, 12), -(std::int64_t{1} << 30));
  EXPECT_EQ(snap_coordinate(1e300, 4), std::int64_t{1} << 22);
}

TEST(QuadDecomposition, ProfileChoosesTheDiagonal) {
  // A 2x2 window filled by one quad v0 (0,0), v1 (2,0), v2 (2,2), v3 (0,2), red 1 at v0 and 0
  // elsewhere (w = 1: screen-linear). By hand, red at the pixel centres:
  //  fan (v0,v1,v2), (v0,v2,v3) — diagonal v0-v2: (0.5,0.5) 0.75, (1.5,0.5) 0.25, (0.5,1.5) 0.25,
  //    (1.5,1.5) 0.25 -> 191, 64, 64, 64;
  //  pairs (v0,v1,v3), (v1,v2,v3) — diagonal v1-v3: 1 − x/2 − y/2 inside the first, 0 beyond:
  //    (0.5,0.5) 0.5 -> 128 (127.5 ties up), the other three 0.
  // The mesa-llvmpipe profile splits immediate-mode quads into pairs and keeps the fan for
  // glDrawArrays (as Mesa 22 does); the default profile always fans.
  const std::array<std::uint32_t, 4> fan{191, 64, 64, 64}, pairs{128, 0, 0, 0};
  auto draw = [](const char* profile, bool arrays) {
    Context ctx(test::small_config(2, 2), *find_profile(profile));
    test::window_projection(ctx);
    const GLfloat xy[8] = {0, 0, 2, 0, 2, 2, 0, 2};
    const GLfloat rgb[12] = {1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    if (arrays) {
      ctx.glEnableClientState(GL_VERTEX_ARRAY);
      ctx.glEnableClientState(GL_COLOR_ARRAY);
      ctx.glVertexPointer(2, GL_FLOAT, 0, xy);
      ctx.glColorPointer(3, GL_FLOAT, 0, rgb);
      ctx.glDrawArrays(GL_QUADS, 0, 4);
    } else {
      ctx.glBegin(GL_QUADS);
      for (int k = 0; k < 4; ++k) {
        ctx.glColor3f(rgb[3 * k], rgb[3 * k + 1], rgb[3 * k + 2]);
        ctx.glVertex2f(xy[2 * k], xy[2 * k + 1]);
      }
      ctx.glEnd();
    }
    return std::array<std::uint32_t, 4>{pixel(ctx, 0, 0)[0], pixel(ctx, 1, 0)[0], pixel(ctx, 0, 1)[0], pixel(ctx, 1, 1)[0]};
  };
  EXPECT_EQ(draw("ideal", false), fan);
  EXPECT_EQ(draw("ideal", true), fan);
  EXPECT_EQ(draw("mesa-llvmpipe", false), pairs);
  EXPECT_EQ(draw("mesa-llvmpipe", true), fan);
}

// f(target) for every lane's target of bands of each of `band_rows` rows in cycles of each of
// `cycles` bands: every first band and every number of bands that fits in the cycle.
template <class F>
void for_each_band_layout(std::initializer_list<int> band_rows, std::initializer_list<int> cycles, F f) {
  for (const int rows : band_rows)
    for (const int cycle : cycles)
      for (int first = 0; first < cycle; ++first)
        for (int count = 1; first + count <= cycle; ++count) {
          RasterTarget t;
          t.band_rows = rows;
          t.band_cycle = cycle;
          t.band_first = first;
          t.band_count = count;
          f(t);
        }
}

std::string layout(const RasterTarget& t) {
  return std::to_string(t.band_rows) + " " + std::to_string(t.band_cycle) + " " + std::to_string(t.band_first) + " " +
         std::to_string(t.band_count);
}

TEST(Raster, RowOwnershipWalksAsOwnsRowDecides) {
  // The incremental walk against RasterTarget::owns_row's definition ((row / band_rows) %
  // band_cycle in [band_first, band_first + band_count)), for every band layout the raster
  // lanes make (1 to 7 lanes, 1 to 15 worker bands) and more, from starting rows across
  // several cycles. A hand-checked case: bands of 8, cycle 4, this lane's bands 1-3: rows
  // 0-7 are not its, 8-31 are, 32-39 not.
  RasterTarget hand;
  hand.band_rows = 8;
  hand.band_cycle = 4;
  hand.band_first = 1;
  hand.band_count = 3;
  RowOwnership walk(hand, 0);
  for (int row = 0; row < 40; ++row, walk.next_row())
    EXPECT_EQ(walk.owned(), row >= 8 && row < 32) << row;
  for_each_band_layout({1, 2, 3, 4, 5, 6, 7, 8, 9}, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
                       [](const RasterTarget& t) {
                         for (std::int64_t start : {0, 1, 7, 8, 37, 500, 1023}) {
                           RowOwnership w(t, start);
                           for (std::int64_t row = start; row < start + 3 * t.band_rows * t.band_cycle + 5;
                                ++row, w.next_row())
                             ASSERT_EQ(w.owned(), t.owns_row(row)) << layout(t) << " row " << row;
                         }
                       });
}

TEST(Raster, OwnsAnyRowIsWhetherAnyOfTheRowsIsOwned) {
  // owns_any_row counts bands in the cycle rather than asking owns_row row by row: the same
  // answer as asking every row, for every range of rows over a few cycles, for lanes owning
  // one or more bands of cycles of several lengths.
  for_each_band_layout({1, 3, 5}, {2, 3, 4, 8}, [](const RasterTarget& t) {
    const int span = 3 * t.band_cycle * t.band_rows;
    for (int a = 0; a < span; ++a)
      for (int b = a; b < span; ++b) {
        bool any = false;
        for (int r = a; r <= b && !any; ++r) any = t.owns_row(r);
        ASSERT_EQ(t.owns_any_row(a, b), any) << layout(t) << " rows " << a << "-" << b;
      }
  });
}
