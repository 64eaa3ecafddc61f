// Rasterization on several threads gives the same bits and counters as on one
// (pipeline/raster_lanes.hpp, docs/threads.md): random scenes through every fragment stage,
// and the papers' programs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pipeline/raster_lanes.hpp"
#include "reports/report.hpp"
#include "programs/programs.hpp"
#include "test_util.hpp"

namespace passim {
namespace {

// Random state groups, each a display list with state changes between its primitives:
// depth, stencil, alpha test, blending (unit and real factors), logic op, masks, scissor,
// fog, a mipmapped or NEAREST texture, points and polygons drawn as points, and markers.
void draw_random_scene(Context& ctx, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-8.0f, 72.0f), z(-1.0f, 1.0f), c(0.0f, 1.0f), st(-0.5f, 1.5f);
  test::window_projection(ctx);
  ctx.glClearStencil(static_cast<GLint>(rng() % 4));
  ctx.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  GLuint tex = 0;
  ctx.glGenTextures(1, &tex);
  ctx.glBindTexture(GL_TEXTURE_2D, tex);
  std::vector<float> texels(16 * 16 * 4);
  for (float& v : texels) v = c(rng);
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA12, 16, 16, 0, GL_RGBA, GL_FLOAT, texels.data());
  for (int level = 1, size = 8; size >= 1; ++level, size /= 2) {
    std::vector<float> small(static_cast<std::size_t>(size * size * 4));
    for (float& v : small) v = c(rng);
    ctx.glTexImage2D(GL_TEXTURE_2D, level, GL_RGBA12, size, size, 0, GL_RGBA, GL_FLOAT, small.data());
  }
  const GLenum funcs[] = {GL_NEVER, GL_LESS, GL_EQUAL, GL_LEQUAL, GL_GREATER, GL_NOTEQUAL, GL_GEQUAL, GL_ALWAYS};
  const GLenum stencil_ops[] = {GL_KEEP, GL_ZERO, GL_REPLACE, GL_INCR, GL_DECR, GL_INVERT};
  const GLenum factors[] = {GL_ZERO, GL_ONE, GL_SRC_ALPHA, GL_ONE_MINUS_DST_ALPHA, GL_DST_COLOR};
  const GLenum equations[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN, GL_MAX};
  const GLenum filters[] = {GL_NEAREST, GL_LINEAR, GL_LINEAR_MIPMAP_LINEAR, GL_NEAREST_MIPMAP_NEAREST};
  auto toggle = [&](GLenum cap, unsigned one_in) { (rng() % one_in == 0) ? ctx.glEnable(cap) : ctx.glDisable(cap); };
  for (int group = 0; group < 4; ++group) {
    const std::string label = "group " + std::to_string(group);
    ctx.glPushGroupMarkerEXT(0, label.c_str());
    const GLuint list = ctx.glGenLists(1);
    ctx.glNewList(list, GL_COMPILE);
    for (int part = 0; part < 3; ++part) {
      toggle(GL_DEPTH_TEST, 4);
      if (rng() % 4) ctx.glEnable(GL_DEPTH_TEST);
      ctx.glDepthFunc(funcs[rng() % 8]);
      ctx.glDepthMask(rng() % 3 != 0);
      toggle(GL_STENCIL_TEST, 3);
      ctx.glStencilFunc(funcs[rng() % 8], static_cast<GLint>(rng() % 4), 0xFF);
      ctx.glStencilOp(stencil_ops[rng() % 6], stencil_ops[rng() % 6], stencil_ops[rng() % 6]);
      toggle(GL_ALPHA_TEST, 4);
      ctx.glAlphaFunc(funcs[rng() % 8], c(rng));
      toggle(GL_BLEND, 2);
      ctx.glBlendEquation(equations[rng() % 5]);
      ctx.glBlendFunc(factors[rng() % 5], factors[rng() % 5]);
      toggle(GL_COLOR_LOGIC_OP, 6);
      ctx.glLogicOp(GL_XOR);
      ctx.glColorMask(rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0);
      toggle(GL_SCISSOR_TEST, 4);
      ctx.glScissor(static_cast<int>(rng() % 30), static_cast<int>(rng() % 20), 30, 25);
      toggle(GL_FOG, 4);
      ctx.glFogi(GL_FOG_MODE, GL_LINEAR);
      ctx.glFogf(GL_FOG_START, 0.0f);
      ctx.glFogf(GL_FOG_END, 1.5f);
      toggle(GL_TEXTURE_2D, 2);
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filters[rng() % 4]));
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, rng() % 2 ? GL_NEAREST : GL_LINEAR);
      ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, rng() % 2 ? GL_REPLACE : GL_MODULATE);
      ctx.glShadeModel(rng() % 2 ? GL_FLAT : GL_SMOOTH);
      ctx.glPolygonMode(GL_FRONT_AND_BACK, rng() % 8 ? GL_FILL : GL_POINT);
      ctx.glPointSize(static_cast<float>(1 + rng() % 3));
      ctx.glBegin(rng() % 6 ? GL_TRIANGLES : GL_POINTS);
      for (int v = 0; v < 3 * 80; ++v) {  // more than RasterLanes::kChunk triangles
        ctx.glColor4f(c(rng), c(rng), c(rng), c(rng));
        ctx.glTexCoord2f(st(rng), st(rng));
        ctx.glVertex3f(pos(rng), pos(rng), z(rng));
      }
      ctx.glEnd();
    }
    ctx.glEndList();
    ctx.glCallList(list);
    ctx.glPopGroupMarkerEXT();
  }
}

TEST(Threads, RandomScenesAreTheSameOnAnyNumberOfThreads) {
  const std::uint64_t runs_before = RasterLanes::threaded_runs;
  for (int bits : {5, 8, 12}) {
    for (unsigned seed = 1; seed <= 12; ++seed) {
      Context one(test::small_config(64, 48, bits));
      draw_random_scene(one, seed);
      for (int threads : {2, 3, 7}) {
        Context many(test::small_config(64, 48, bits));
        many.set_threads(threads);
        ASSERT_EQ(many.threads(), threads);
        draw_random_scene(many, seed);
        const Framebuffer &a = one.framebuffer(), &b = many.framebuffer();
        ASSERT_EQ(a.color[0].rgba, b.color[0].rgba) << bits << " bits, seed " << seed << ", " << threads << " threads";
        ASSERT_EQ(a.depth, b.depth) << bits << " " << seed << " " << threads;
        ASSERT_EQ(a.stencil, b.stencil) << bits << " " << seed << " " << threads;
        ASSERT_EQ(one.passes().size(), many.passes().size());
        for (std::size_t p = 0; p < one.passes().size(); ++p)
          ASSERT_TRUE(one.passes()[p].counters == many.passes()[p].counters)
              << bits << " " << seed << " " << threads << " pass " << one.passes()[p].label;
        ASSERT_TRUE(one.total_counters() == many.total_counters());
        ASSERT_EQ(one.error_log().size(), many.error_log().size());
      }
    }
  }
  EXPECT_GT(RasterLanes::threaded_runs - runs_before, 100u);  // the lanes did run in parallel
}

TEST(Threads, DisplayListTriangleBlocksAreTheSameOnAnyNumberOfThreads) {
  // Context::draw_triangle_batch: a list's glBegin(GL_TRIANGLES) block of glNormal3d and
  // glVertex4d calls has its distinct vertices transformed once and its triangles assembled,
  // on every lane. Lit, culled, clipped (some vertices far outside the view, some behind the
  // eye), normals inherited from before the block for its first vertices (the current normal
  // differs between calls of the list) and then changed every few vertices, vertices and
  // normals drawn from small pools (so that each recurs, in triangles drawn and clipped, with
  // the same normal and with another, inherited or set), texgen on for some seeds, two
  // vertices left over after the last triangle; the state after the lists (current normal),
  // the planes, the counters and the warnings must be those of the same calls made one by one
  // outside a list (immediate mode, one thread), on one thread and on several.
  const std::uint64_t tasks_before = RasterLanes::tasks_run;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    auto run = [&](int threads, bool immediate) {
      auto ctx = std::make_unique<Context>(test::small_config(64, 48, 12));
      ctx->set_threads(threads);
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> pos(-1.6, 1.6), z(-3.0, 0.4), unit(-1.0, 1.0);
      ctx->glMatrixMode(GL_PROJECTION);
      ctx->gluPerspective(60.0, 64.0 / 48.0, 0.5, 10.0);
      ctx->glMatrixMode(GL_MODELVIEW);
      ctx->glTranslated(0.0, 0.0, -2.0);
      ctx->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      ctx->glEnable(GL_DEPTH_TEST);
      ctx->glEnable(GL_LIGHTING);
      ctx->glEnable(GL_LIGHT0);
      ctx->glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, seed % 2);
      if (seed % 3 == 0) ctx->glEnable(GL_CULL_FACE);
      if (seed % 2 == 0) {
        ctx->glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
        ctx->glEnable(GL_TEXTURE_GEN_S);
      }
      ctx->glNormal3d(0.0, 0.0, 1.0);  // inherited by the block's first vertices
      ctx->glEnable(GL_TEXTURE_2D);     // incomplete: the stage setup warns, at the first triangle drawn
      std::vector<Vec4> positions(40);
      for (Vec4& p : positions) p = Vec4(pos(rng), pos(rng), z(rng), 1.0);
      std::vector<Vec3> normals{{0.0, 0.0, 1.0}, {0.0, 0.0, 1.0}};  // the inherited one, set
      for (int k = 0; k < 4; ++k) normals.emplace_back(unit(rng), unit(rng), unit(rng));
      // A block: its glNormal3d (w = 0 marks them) and glVertex4d calls.
      auto make_block = [&](int nan_vertex) {
        std::vector<Vec4> block;
        const int vertices = 3 * 150 + 2;
        for (int k = 0; k < vertices; ++k) {
          if (k >= 4 && rng() % 3 == 0) block.push_back(Vec4(normals[rng() % normals.size()], 0.0));
          const Vec4& p = positions[rng() % positions.size()];
          block.push_back(Vec4(k == nan_vertex ? std::nan("") : p.x, p.y, p.z, p.w));
        }
        return block;
      };
      auto draw = [&](const std::vector<Vec4>& block) {
        ctx->glBegin(GL_TRIANGLES);
        for (const Vec4& c : block) c.w == 0.0 ? ctx->glNormal3d(c.x, c.y, c.z) : ctx->glVertex4d(c.x, c.y, c.z, c.w);
        ctx->glEnd();
      };
      auto compile = [&](const std::vector<Vec4>& block) {
        const GLuint list = ctx->glGenLists(1);
        ctx->glNewList(list, GL_COMPILE);
        draw(block);
        ctx->glEndList();
        return list;
      };
      // A vertex with a NaN coordinate (a warning where its triangle is met): in the first
      // triangle for odd seeds, the 101st for even ones.
      const std::vector<Vec4> first = make_block(seed % 2 ? 1 : 301);
      const std::vector<Vec4> others[2] = {make_block(-1), make_block(-1)};
      if (immediate) {
        draw(first);
        ctx->glNormal3d(0.3, -0.5, 0.8);
        for (const auto* block : {&first, &first, &others[0], &others[1]}) draw(*block);
        return ctx;
      }
      const GLuint list = compile(first);
      ctx->glCallList(list);
      ctx->glNormal3d(0.3, -0.5, 0.8);  // the block's first vertices now take this one
      ctx->glCallList(list);
      // Three blocks in one call, under the same state: queued one after the other by
      // reference (two sets of chunks in turn: the third block's must wait for the first's).
      const GLuint inner[2] = {compile(others[0]), compile(others[1])};
      const GLuint outer = ctx->glGenLists(1);
      ctx->glNewList(outer, GL_COMPILE);
      ctx->glCallList(list);
      ctx->glCallList(inner[0]);
      ctx->glCallList(inner[1]);
      ctx->glEndList();
      ctx->glCallList(outer);
      return ctx;
    };
    const auto one = run(1, true);
    for (int threads : {1, 2, 3}) {
      const auto many = run(threads, false);
      ASSERT_EQ(one->framebuffer().color[0].rgba, many->framebuffer().color[0].rgba) << seed << " " << threads;
      ASSERT_EQ(one->framebuffer().depth, many->framebuffer().depth) << seed << " " << threads;
      ASSERT_TRUE(one->total_counters() == many->total_counters()) << seed << " " << threads;
      GLdouble a[4] = {}, b[4] = {};
      one->glGetDoublev(GL_CURRENT_NORMAL, a);
      many->glGetDoublev(GL_CURRENT_NORMAL, b);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(a[k], b[k]) << seed;
      EXPECT_EQ(one->warnings(), many->warnings()) << seed << " " << threads;  // and in the same order
      EXPECT_EQ(one->warnings().size(), 2u) << seed;
      EXPECT_EQ(many->glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    }
    EXPECT_GT(one->total_counters().primitives_clipped, 0u) << seed;  // the cases are there
    EXPECT_GT(one->total_counters().fragments_written, 0u) << seed;
  }
  EXPECT_GE(RasterLanes::tasks_run - tasks_before, 24u);  // the blocks did take the lanes' path
}

// A context on `threads` threads holding a random scene (draw_random_scene), its errors cleared.
std::unique_ptr<Context> random_scene_context(unsigned seed, int threads) {
  auto ctx = std::make_unique<Context>(test::small_config(72, 56, 8 + static_cast<int>(seed % 5)));
  ctx->set_threads(threads);
  draw_random_scene(*ctx, seed);
  while (ctx->glGetError() != GL_NO_ERROR) {
  }  // the scene's own (not the test's)
  return ctx;
}

// Random pixel transfer: a scale and a bias, a colour table (enabled or not) and a colour matrix.
void random_transfer(Context& ctx, std::mt19937& rng, GLenum scale, GLenum bias, GLenum table_target,
                     GLenum table_format, int table_size, bool table_enabled) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  ctx.glPixelTransferf(scale, 0.5f + unit(rng));
  ctx.glPixelTransferf(bias, unit(rng) - 0.5f);
  std::vector<float> table(4 * static_cast<std::size_t>(table_size));
  for (float& v : table) v = unit(rng);
  ctx.glColorTable(table_target, table_format, table_size, GL_RGBA, GL_FLOAT, table.data());
  if (table_enabled) ctx.glEnable(table_target);
  GLdouble matrix[16];
  for (double& v : matrix) v = unit(rng) * 0.6;
  ctx.glMatrixMode(GL_COLOR);
  ctx.glLoadMatrixd(matrix);
  ctx.glMatrixMode(GL_MODELVIEW);
}

TEST(Threads, PixelCopiesAreTheSameOnAnyNumberOfThreads) {
  // glCopyPixels's bands on the lanes (Context::copy_bands_on_lanes): random scenes copied
  // through scale and bias, a colour table, the colour matrix, pixel zoom (up, down and
  // mirrored), blending, colour masks and whatever texture, scissor and logic-op state the
  // scene left, onto themselves and elsewhere.
  const std::uint64_t tasks_before = RasterLanes::tasks_run;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    auto run = [&](int threads) {
      auto ctx = random_scene_context(seed, threads);
      std::mt19937 rng(seed * 7u);
      std::uniform_real_distribution<float> unit(0.0f, 1.0f);
      if (seed % 2 == 0) ctx->glDisable(GL_TEXTURE_2D);  // otherwise rectangles are textured too
      ctx->glDisable(GL_DEPTH_TEST);
      ctx->glDisable(GL_STENCIL_TEST);
      ctx->glDisable(GL_ALPHA_TEST);
      ctx->glDisable(GL_FOG);
      ctx->glMatrixMode(GL_PROJECTION);
      ctx->glLoadIdentity();
      ctx->glOrtho(0, 72, 0, 56, -1, 1);
      ctx->glMatrixMode(GL_MODELVIEW);
      ctx->glLoadIdentity();
      random_transfer(*ctx, rng, GL_RED_SCALE, GL_ALPHA_BIAS, GL_COLOR_TABLE, GL_RGBA8, 256, seed % 2);
      const float zooms[] = {1.0f, 2.0f, 0.5f, -1.0f, 1.5f};
      ctx->glPixelZoom(zooms[seed % 5], zooms[(seed / 2) % 5]);
      if (seed % 3 == 0) {
        ctx->glEnable(GL_BLEND);
        ctx->glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
      }
      ctx->glColorMask(GL_TRUE, seed % 4 != 0, GL_TRUE, GL_TRUE);
      ctx->glRasterPos2i(static_cast<GLint>(rng() % 20), static_cast<GLint>(rng() % 20));
      ctx->glCopyPixels(static_cast<GLint>(rng() % 10), static_cast<GLint>(rng() % 10), 60, 45, GL_COLOR);
      ctx->glRasterPos2i(0, 0);
      ctx->glCopyPixels(0, 0, 72, 56, GL_COLOR);
      return ctx;
    };
    const auto one = run(1);
    for (int threads : {2, 3}) {
      const auto many = run(threads);
      ASSERT_EQ(one->framebuffer().color[0].rgba, many->framebuffer().color[0].rgba) << seed << " " << threads;
      ASSERT_TRUE(one->total_counters() == many->total_counters()) << seed << " " << threads;
      EXPECT_EQ(many->glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << seed;
    }
    EXPECT_GT(one->total_counters().pixels_color_matrix, 0u) << seed;
    EXPECT_GT(one->total_counters().fragments_written, 0u) << seed;
  }
  EXPECT_GE(RasterLanes::tasks_run - tasks_before, 32u);  // the copies did take the lanes' path
}

TEST(Threads, ClearsAreTheSameOnAnyNumberOfThreads) {
  // glClear's rows on the lanes (Context::rows_on_lanes): every plane, under a scissor box or
  // not, colour, depth and stencil write masks, over a random scene. The cleared values are
  // the spec's (§2.13.9 conversion, A8 rounding, worked by hand: 0.5, 0.25, 1, 0 at b bits are
  // 2^(b−1), 2^(b−2), 2^b − 1, 0); what the box or the masks keep is what was there before.
  const std::uint64_t tasks_before = RasterLanes::tasks_run;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const bool scissor = seed % 2 == 1;
    const GLboolean green = seed % 3 != 0, depth_mask = seed % 4 != 0;
    const int bits = 8 + static_cast<int>(seed % 5);  // random_scene_context's colour width
    std::unique_ptr<Context> before;
    auto run = [&](int threads) {
      auto ctx = random_scene_context(seed, threads);
      if (threads == 1) {  // a copy of what the clear starts from
        before = random_scene_context(seed, 1);
      }
      if (scissor) {
        ctx->glEnable(GL_SCISSOR_TEST);
        ctx->glScissor(5, 7, 50, 40);
      } else {
        ctx->glDisable(GL_SCISSOR_TEST);
      }
      ctx->glColorMask(GL_TRUE, green, GL_TRUE, GL_TRUE);
      ctx->glDepthMask(depth_mask);
      ctx->glStencilMask(0x0F);
      ctx->glClearColor(0.5f, 0.25f, 1.0f, 0.0f);
      ctx->glClearDepth(0.5);
      ctx->glClearStencil(0xA5);
      ctx->glClearAccum(0.5f, -0.5f, 0.0f, 1.0f);
      ctx->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT | GL_ACCUM_BUFFER_BIT);
      return ctx;
    };
    const auto one = run(1);
    for (int threads : {2, 3}) {
      const auto many = run(threads);
      const Framebuffer &a = one->framebuffer(), &b = many->framebuffer();
      ASSERT_EQ(a.color[0].rgba, b.color[0].rgba) << seed << " " << threads;
      ASSERT_EQ(a.depth, b.depth) << seed << " " << threads;
      ASSERT_EQ(a.stencil, b.stencil) << seed << " " << threads;
      ASSERT_EQ(a.accum, b.accum) << seed << " " << threads;
      ASSERT_TRUE(one->total_counters() == many->total_counters()) << seed << " " << threads;
      EXPECT_EQ(many->glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << seed;
    }
    const Framebuffer &fb = one->framebuffer(), &old = before->framebuffer();
    const std::uint32_t expected[4] = {1u << (bits - 1), 1u << (bits - 2), (1u << bits) - 1, 0};
    for (int y = 0; y < 56; ++y)
      for (int x = 0; x < 72; ++x) {
        const bool inside = !scissor || (x >= 5 && x < 55 && y >= 7 && y < 47);
        const std::size_t p = fb.pixel_index(x, y);
        for (int k = 0; k < 4; ++k) {
          const bool written = inside && (k != 1 || green);
          ASSERT_EQ(fb.color[0].rgba[4 * p + k], written ? expected[k] : old.color[0].rgba[4 * p + k])
              << seed << " " << x << "," << y << " " << k;
        }
        ASSERT_EQ(fb.depth[p], inside && depth_mask ? (1u << 23) : old.depth[p]) << seed;  // round(0.5·(2^24 − 1))
        ASSERT_EQ(fb.stencil[p], inside ? ((old.stencil[p] & 0xF0) | 0x05) : old.stencil[p]) << seed;
      }
  }
  EXPECT_GE(RasterLanes::tasks_run - tasks_before, 6u);  // the clears did take the lanes' path
}

TEST(Threads, TextureCopiesAreTheSameOnAnyNumberOfThreads) {
  // Copies to colour textures in bands on the lanes (Context::copy_color_texels): random
  // scenes copied through scale and bias, a colour table and the colour matrix into textures
  // of several internal formats, whole (glCopyTexImage2D) and in part (glCopyTexSubImage2D),
  // and, on the calling thread alone, with a convolution.
  const std::uint64_t tasks_before = RasterLanes::tasks_run;
  const GLenum formats[] = {GL_RGBA8, GL_RGBA12, GL_LUMINANCE12_ALPHA4, GL_RGB5_A1, GL_INTENSITY16};
  for (unsigned seed = 1; seed <= 6; ++seed) {
    auto run = [&](int threads) {
      auto ctx = random_scene_context(seed, threads);
      std::mt19937 rng(seed * 11u);
      std::uniform_real_distribution<float> unit(0.0f, 1.0f);
      random_transfer(*ctx, rng, GL_GREEN_SCALE, GL_BLUE_BIAS, GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_RGBA12, 64,
                      seed % 2);
      GLuint tex[2];
      ctx->glGenTextures(2, tex);
      ctx->glBindTexture(GL_TEXTURE_2D, tex[0]);
      const GLenum format = formats[seed % 5];
      ctx->glCopyTexImage2D(GL_TEXTURE_2D, 0, format, static_cast<GLint>(rng() % 8), static_cast<GLint>(rng() % 8), 64,
                            32, 0);
      ctx->glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 3, 5, static_cast<GLint>(rng() % 20), 2, 40, 20);
      ctx->glBindTexture(GL_TEXTURE_2D, tex[1]);
      const bool convolved = seed % 3 == 0;
      if (convolved) {  // a 3x3 convolution (REDUCE: 34 → 32): the whole rectangle on the calling thread
        std::vector<float> kernel(9 * 4);
        for (float& v : kernel) v = unit(rng) * 0.2f;
        ctx->glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, kernel.data());
        ctx->glEnable(GL_CONVOLUTION_2D);
      }
      ctx->glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA12, 0, 0, convolved ? 34 : 32, convolved ? 34 : 32, 0);
      std::vector<std::vector<float>> texels(2, std::vector<float>(4 * 64 * 32));
      for (int k = 0; k < 2; ++k) {
        ctx->glBindTexture(GL_TEXTURE_2D, tex[k]);
        ctx->glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_FLOAT, texels[static_cast<std::size_t>(k)].data());
      }
      EXPECT_EQ(ctx->glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << seed << " " << threads;
      return std::make_pair(std::move(ctx), texels);
    };
    const auto [one, one_texels] = run(1);
    for (int threads : {2, 3}) {
      const auto [many, many_texels] = run(threads);
      ASSERT_EQ(one_texels, many_texels) << seed << " " << threads;
      ASSERT_TRUE(one->total_counters() == many->total_counters()) << seed << " " << threads;
    }
    EXPECT_GT(one->total_counters().pixels_color_matrix, 0u) << seed;
    EXPECT_GT(one->total_counters().texture_bits_written, 0u) << seed;
  }
  EXPECT_GE(RasterLanes::tasks_run - tasks_before, 2u * 2u * 6u);  // the copies did take the lanes' path
}

TEST(Threads, ProgramsGiveTheSameImagesAndCountersOnAnyNumberOfThreads) {
  struct Case {
    const char* program;
    int filter, depths;
    const char* scene;
    bool linear;
  };
  for (const Case& c : {Case{"shadow-map", 0, 1, "paper", false}, Case{"fast-pcf", 4, 1, "paper", false},
                        Case{"pcf", 2, 1, "edges", false}, Case{"mdsm", 2, 2, "edges", false},
                        Case{"hw-shadow", 0, 1, "edges", true}}) {
    auto run = [&](int threads) {
      ProgramOptions o;
      o.program = c.program;
      o.filter = c.filter;
      o.depths = c.depths;
      o.scene = c.scene;
      o.linear = c.linear;
      o.color_bits = 12;
      o.threads = threads;
      return run_program(o);
    };
    const ProgramRun one = run(1);
    for (int threads : {2, 3}) {
      const ProgramRun many = run(threads);
      ASSERT_EQ(one.result.images.size(), many.result.images.size());
      for (std::size_t k = 0; k < one.result.images.size(); ++k)
        EXPECT_EQ(one.result.images[k].hash, many.result.images[k].hash)
            << c.program << " " << threads << " threads: " << one.result.images[k].name;
      const nlohmann::json a = run_report(one.result, "one", {}), b = run_report(many.result, "many", {});
      EXPECT_EQ(a["passes"], b["passes"]) << c.program << " " << threads << " threads";
      EXPECT_EQ(a["total"], b["total"]) << c.program << " " << threads << " threads";
      EXPECT_EQ(a["warnings"], b["warnings"]) << c.program << " " << threads << " threads";
      EXPECT_EQ(one.trace, many.trace) << c.program;
    }
  }
}

TEST(Threads, SettingTheNumberIsClampedAndKeepsWhatWasDrawn) {
  Context ctx(test::small_config(8, 8));
  EXPECT_EQ(ctx.threads(), 1);
  ctx.set_threads(0);
  EXPECT_EQ(ctx.threads(), 1);
  ctx.set_threads(1000);
  EXPECT_EQ(ctx.threads(), Context::kMaxThreads);
  // A Begin/End left open keeps its primitives queued; changing the number of threads
  // runs them first (a red full-window quad: every pixel 255, 0, 0).
  test::window_projection(ctx);
  ctx.glColor3f(1, 0, 0);
  ctx.glBegin(GL_QUADS);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(8, 0);
  ctx.glVertex2f(8, 8);
  ctx.glVertex2f(0, 8);
  ctx.set_threads(2);
  EXPECT_EQ(test::pixel(ctx, 3, 5)[0], 255u);
  ctx.glEnd();
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace passim
