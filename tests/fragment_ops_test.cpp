// Per-fragment operations (§4.1) with hand-computed values at 8 and 12 bits.
#include <gtest/gtest.h>

#include <optional>

#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {
void full_quad(Context& c) {
  const auto& cfg = c.config();
  c.glBegin(GL_QUADS);
  c.glVertex2f(0, 0);
  c.glVertex2f(static_cast<float>(cfg.width), 0);
  c.glVertex2f(static_cast<float>(cfg.width), static_cast<float>(cfg.height));
  c.glVertex2f(0, static_cast<float>(cfg.height));
  c.glEnd();
}
}  // namespace

TEST(Blend, ReverseSubtractClampsAtZero) {
  for (int bits : {8, 12}) {
    Context ctx(test::small_config(2, 2, bits));
    test::window_projection(ctx);
    ctx.glClearColor(0.5f, 0.25f, 1.0f, 1.0f);
    ctx.glClear(GL_COLOR_BUFFER_BIT);
    ctx.glEnable(GL_BLEND);
    ctx.glBlendFunc(GL_ONE, GL_ONE);
    ctx.glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    ctx.glColor4f(0.75f, 0.125f, 0.5f, 0.0f);
    full_quad(ctx);
    // d - s with d, s the fixed-point values: bits 8: d = (128, 64, 255)/255, s = (191, 32, 128)/255
    // (0.75·255 = 191.25, 0.125·255 = 31.875, 0.5·255 = 127.5 -> 128):
    // R 128-191 < 0 -> 0; G 64-32 = 32; B 255-128 = 127; A 255-0 = 255.
    // bits 12: d = (2048, 1024, 4095), s = (3071, 512, 2048): R 0, G 512, B 2047, A 4095.
    const auto p = pixel(ctx, 0, 0);
    if (bits == 8) {
      EXPECT_EQ(p, (std::array<std::uint32_t, 4>{0, 32, 127, 255}));
    } else {
      EXPECT_EQ(p, (std::array<std::uint32_t, 4>{0, 512, 2047, 4095}));
    }
  }
}

TEST(Blend, MinMaxIgnoreFactors) {
  Context ctx(test::small_config(2, 2, 8));
  test::window_projection(ctx);
  ctx.glClearColor(0.2f, 0.8f, 0.4f, 0.6f);  // codes 51, 204, 102, 153
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glEnable(GL_BLEND);
  ctx.glBlendFunc(GL_ZERO, GL_ZERO);  // would give 0 if the factors applied
  ctx.glBlendEquation(GL_MAX);
  ctx.glColor4f(0.6f, 0.2f, 0.4f, 1.0f);  // codes 153, 51, 102, 255
  full_quad(ctx);
  EXPECT_EQ(pixel(ctx, 1, 1), (std::array<std::uint32_t, 4>{153, 204, 102, 255}));
  ctx.glBlendEquation(GL_MIN);
  ctx.glColor4f(0.0f, 1.0f, 0.2f, 0.0f);  // 0, 255, 51, 0
  full_quad(ctx);
  EXPECT_EQ(pixel(ctx, 1, 1), (std::array<std::uint32_t, 4>{0, 204, 51, 0}));
}

TEST(Blend, ConstantColourAndAlphaFactors) {
  // s·Ac + d·(1 - Ac) with Ac = 0.25 (imaging subset's CONSTANT_ALPHA), 8 bits:
  // s = 255/255, d = 0 -> 0.25·255 = 63.75 -> 64.
  Context ctx(test::small_config(2, 2, 8));
  test::window_projection(ctx);
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glEnable(GL_BLEND);
  ctx.glBlendColor(0, 0, 0, 0.25f);
  ctx.glBlendFunc(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA);
  ctx.glColor4f(1, 1, 1, 1);
  full_quad(ctx);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 64u);
  // Again: d = 64/255: 0.25 + 0.75·64/255 = 0.43824 -> 111.75 -> 112.
  full_quad(ctx);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 112u);
}

TEST(ColorMask, EveryChannelCombination) {
  for (int mask = 0; mask < 16; ++mask) {
    Context ctx(test::small_config(1, 1, 12));
    test::window_projection(ctx);
    ctx.glClearColor(0, 0, 0, 0);
    ctx.glClear(GL_COLOR_BUFFER_BIT);
    const std::uint64_t cleared = ctx.total_counters().color_bits_written;  // 4 x 12
    ctx.glColorMask(mask & 1, (mask >> 1) & 1, (mask >> 2) & 1, (mask >> 3) & 1);
    ctx.glColor4f(1, 1, 1, 1);
    full_quad(ctx);
    const auto p = pixel(ctx, 0, 0);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(p[k], ((mask >> k) & 1) ? 4095u : 0u) << "mask " << mask;
    EXPECT_EQ(cleared, 48u);
    EXPECT_EQ(ctx.total_counters().color_bits_written - cleared,
              static_cast<std::uint64_t>(12 * __builtin_popcount(static_cast<unsigned>(mask))));
  }
}

TEST(Dither, EnabledByDefaultAndStoredAsState) {
  // Table 6.20: DITHER is enabled initially; it is state that IsEnabled and GetBooleanv report.
  // A3: no stage reads it (colours are rounded once), so it has no test of its effect.
  Context ctx(test::small_config(8, 8, 8));
  EXPECT_EQ(ctx.glIsEnabled(GL_DITHER), GL_TRUE);
  ctx.glDisable(GL_DITHER);
  EXPECT_EQ(ctx.glIsEnabled(GL_DITHER), GL_FALSE);
  GLboolean b = GL_TRUE;
  ctx.glGetBooleanv(GL_DITHER, &b);
  EXPECT_EQ(b, GL_FALSE);
  ctx.glEnable(GL_DITHER);
  EXPECT_EQ(ctx.glIsEnabled(GL_DITHER), GL_TRUE);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(AlphaWidth, FewerThanTwoAlphaBitsCarryAlphaAtRgbPrecision) {
  // A26: framebuffer alpha 0 bits; fragment alpha kept at 8 bits for the alpha test,
  // destination alpha reads as 1.
  FramebufferConfig cfg = test::small_config(2, 1, 8);
  cfg.color_bits[3] = 0;
  Context ctx(cfg);
  test::window_projection(ctx);
  ctx.glEnable(GL_ALPHA_TEST);
  ctx.glAlphaFunc(GL_GREATER, 0.5f);  // ref code 128
  ctx.glBegin(GL_QUADS);
  ctx.glColor4f(1, 1, 1, 129.0f / 255.0f);  // passes: 129 > 128
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(1, 0);
  ctx.glVertex2f(1, 1);
  ctx.glVertex2f(0, 1);
  ctx.glColor4f(1, 1, 1, 128.0f / 255.0f);  // fails: 128 > 128 is false
  ctx.glVertex2f(1, 0);
  ctx.glVertex2f(2, 0);
  ctx.glVertex2f(2, 1);
  ctx.glVertex2f(1, 1);
  ctx.glEnd();
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 255u);
  EXPECT_EQ(pixel(ctx, 1, 0)[0], 0u);
  EXPECT_EQ(ctx.total_counters().killed_alpha, 1u);
  // DST_ALPHA with no alpha plane is 1: ONE·0 + d·... -> source·Ad = source.
  ctx.glDisable(GL_ALPHA_TEST);
  ctx.glEnable(GL_BLEND);
  ctx.glBlendFunc(GL_DST_ALPHA, GL_ZERO);
  ctx.glColor4f(0.5f, 0.5f, 0.5f, 0.0f);
  ctx.glBegin(GL_QUADS);
  ctx.glVertex2f(1, 0);
  ctx.glVertex2f(2, 0);
  ctx.glVertex2f(2, 1);
  ctx.glVertex2f(1, 1);
  ctx.glEnd();
  EXPECT_EQ(pixel(ctx, 1, 0)[0], 128u);
}

TEST(Stencil, OperationsSaturateAndMasksApply) {
  Context ctx(test::small_config(1, 1, 8));
  test::window_projection(ctx);
  ctx.glClearStencil(254);
  ctx.glClear(GL_STENCIL_BUFFER_BIT);
  ctx.glEnable(GL_STENCIL_TEST);
  ctx.glStencilFunc(GL_ALWAYS, 0, 0xFF);
  ctx.glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  for (int k = 0; k < 3; ++k) full_quad(ctx);  // 254 -> 255 -> 255 -> 255 (saturates, GL 1.2)
  EXPECT_EQ(ctx.framebuffer().stencil[0], 255u);
  ctx.glStencilMask(0x0F);
  ctx.glStencilOp(GL_KEEP, GL_KEEP, GL_ZERO);
  full_quad(ctx);  // only the low 4 bits are written: 0xF0
  EXPECT_EQ(ctx.framebuffer().stencil[0], 0xF0u);
  ctx.glStencilFunc(GL_EQUAL, 0x30, 0x30);  // (0x30 & 0x30) == (0xF0 & 0x30): passes
  ctx.glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  full_quad(ctx);
  ctx.glStencilFunc(GL_LESS, 0xF0, 0xFF);  // 0xF0 < 0xF0 false: killed
  full_quad(ctx);
  EXPECT_EQ(ctx.total_counters().killed_stencil, 1u);
}

TEST(LogicOp, XorOnCodes) {
  Context ctx(test::small_config(1, 1, 12));
  test::window_projection(ctx);
  ctx.glClearColor(1, 0, 1, 0);  // 4095, 0, 4095, 0
  ctx.glClear(GL_COLOR_BUFFER_BIT);
  ctx.glEnable(GL_COLOR_LOGIC_OP);
  ctx.glLogicOp(GL_XOR);
  ctx.glColor4f(0.5f, 0.5f, 0, 1);  // 2048, 2048, 0, 4095
  full_quad(ctx);
  EXPECT_EQ(pixel(ctx, 0, 0), (std::array<std::uint32_t, 4>{4095u ^ 2048u, 2048, 4095, 4095}));
}

TEST(FlatShading, ProvokingVertexIsLastForTrianglesFirstForPolygons) {
  Context ctx(test::small_config(4, 4, 8));
  test::window_projection(ctx);
  ctx.glShadeModel(GL_FLAT);
  ctx.glBegin(GL_TRIANGLES);
  ctx.glColor3f(1, 0, 0);
  ctx.glVertex2f(0, 0);
  ctx.glColor3f(0, 1, 0);
  ctx.glVertex2f(4, 0);
  ctx.glColor3f(0, 0, 1);
  ctx.glVertex2f(0, 4);
  ctx.glEnd();
  EXPECT_EQ(pixel(ctx, 0, 0), (std::array<std::uint32_t, 4>{0, 0, 255, 255}));
  ctx.glBegin(GL_POLYGON);
  ctx.glColor3f(1, 0, 0);
  ctx.glVertex2f(0, 0);
  ctx.glColor3f(0, 1, 0);
  ctx.glVertex2f(4, 0);
  ctx.glColor3f(0, 0, 1);
  ctx.glVertex2f(4, 4);
  ctx.glEnd();
  EXPECT_EQ(pixel(ctx, 3, 0), (std::array<std::uint32_t, 4>{255, 0, 0, 255}));
}

#include <random>

#include "stages/fragment_ops.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/kernel_paths.hpp"

TEST(FastPath, ReplacePathMatchesTheGeneralPath) {
  // Random triangles under random depth functions, depth masks, colour masks, scissor, blend:
  // planes and counters must be identical with and without the specialised path.
  const GLenum funcs[] = {GL_NEVER, GL_LESS, GL_EQUAL, GL_LEQUAL, GL_GREATER, GL_NOTEQUAL, GL_GEQUAL, GL_ALWAYS};
  auto draw = [&](Context& ctx, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-4.0f, 36.0f), z(-1.0f, 1.0f), c(0.0f, 1.0f);
    test::window_projection(ctx);
    ctx.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int k = 0; k < 60; ++k) {
      if (k % 6 == 0) {
        (rng() % 4) ? ctx.glEnable(GL_DEPTH_TEST) : ctx.glDisable(GL_DEPTH_TEST);
        ctx.glDepthFunc(funcs[rng() % 8]);
        ctx.glDepthMask(rng() % 3 != 0);
        ctx.glColorMask(rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0);
        (rng() % 3 == 0) ? ctx.glEnable(GL_SCISSOR_TEST) : ctx.glDisable(GL_SCISSOR_TEST);
        ctx.glScissor(static_cast<int>(rng() % 16), static_cast<int>(rng() % 16), 10, 12);
        ctx.glShadeModel(rng() % 2 ? GL_FLAT : GL_SMOOTH);
        // Blending with unit factors takes the integer blend; others the real arithmetic.
        const GLenum factors[] = {GL_ZERO, GL_ONE, GL_ONE_MINUS_DST_ALPHA, GL_SRC_ALPHA};
        const GLenum equations[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN, GL_MAX};
        (rng() % 2) ? ctx.glEnable(GL_BLEND) : ctx.glDisable(GL_BLEND);
        ctx.glBlendEquation(equations[rng() % 5]);
        ctx.glBlendFunc(factors[rng() % (rng() % 3 ? 2 : 4)], factors[rng() % (rng() % 3 ? 2 : 4)]);
      }
      ctx.glBegin(GL_TRIANGLES);
      for (int v = 0; v < 3; ++v) {
        ctx.glColor4f(c(rng), c(rng), c(rng), c(rng));
        ctx.glVertex3f(pos(rng), pos(rng), z(rng));
      }
      ctx.glEnd();
    }
  };
  std::optional<ScopedKernelPaths> paths;  // the general paths for the second drawing
  for (int bits : {8, 12}) {
    for (unsigned seed = 1; seed <= 20; ++seed) {
      Context fast(test::small_config(32, 32, bits)), general(test::small_config(32, 32, bits));
      draw(fast, seed);
      paths.emplace(KernelPaths{KernelPaths::Simd::Avx2, false});
      draw(general, seed);
      paths.reset();
      ASSERT_EQ(fast.framebuffer().color[0].rgba, general.framebuffer().color[0].rgba) << seed;
      ASSERT_EQ(fast.framebuffer().depth, general.framebuffer().depth) << seed;
      ASSERT_TRUE(fast.total_counters() == general.total_counters()) << seed;
    }
  }
}

TEST(Blend, UnitFactorsInIntegersEqualTheRealArithmetic) {
  // The integer blend for factors 0/1 (and MIN/MAX) against §4.1.6 in reals rounded by
  // §2.13.9, with and without the products rounded: every 8-bit pair, random 12/16-bit
  // pairs and the pairs whose sum or difference sits at the ends of the range.
  const GLenum equations[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN, GL_MAX};
  auto check = [&](int bits, std::uint32_t a, std::uint32_t b) {
    const std::uint32_t m = max_code(bits);
    for (GLenum eq : equations)
      for (int sf = 0; sf < 2; ++sf)
        for (int df = 0; df < 2; ++df)
          for (int rounded : {0, bits}) {
            const double real = blend_component(eq, fixed_to_float(a, bits), fixed_to_float(b, bits), sf, df, rounded);
            const std::uint32_t want = float_to_fixed(real, bits);
            const std::uint32_t got = blend_codes_unit_factors(eq, sf == 1, df == 1, a, b, m);
            if (got != want) {
              ADD_FAILURE() << bits << " bits, eq " << eq << " sf " << sf << " df " << df << ": " << a << ", " << b
                            << " -> " << got << " want " << want;
              return false;
            }
          }
    return true;
  };
  for (std::uint32_t a = 0; a < 256; ++a)
    for (std::uint32_t b = 0; b < 256; ++b)
      if (!check(8, a, b)) return;
  std::mt19937 rng(5);
  for (int bits : {12, 16}) {
    const std::uint32_t m = max_code(bits);
    for (int n = 0; n < 20000; ++n)
      if (!check(bits, rng() % (m + 1), rng() % (m + 1))) return;
    for (std::uint32_t a = 0; a <= m; a += (bits == 12 ? 1 : 7)) {
      if (!check(bits, a, m - a) || !check(bits, a, a) || !check(bits, a, m - a + (a > 0 ? 1 : 0))) return;
    }
  }
  EXPECT_TRUE(blend_has_unit_factors(GL_FUNC_ADD, GL_ONE, GL_ZERO));
  EXPECT_TRUE(blend_has_unit_factors(GL_MIN, GL_SRC_ALPHA, GL_DST_COLOR));
  EXPECT_FALSE(blend_has_unit_factors(GL_FUNC_ADD, GL_ONE_MINUS_DST_ALPHA, GL_ONE));
}

TEST(Blend, UnitFactorSpanKernelEqualsTheScalarLoop) {
  // The SSE2 span kernel against the scalar loop of blend_codes_unit_factors (itself checked
  // against the real arithmetic above): every equation and factor pair, random widths, live
  // fragments, written channels, spans of odd and even length and begin.
  std::mt19937 rng(17);
  const GLenum equations[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN, GL_MAX};
  std::uint64_t blended = 0;
  for (int round = 0; round < 3000; ++round) {
    UnitFactorBlend b;
    b.equation = equations[rng() % 5];
    b.src_one = rng() % 2;
    b.dst_one = rng() % 2;
    for (int k = 0; k < 4; ++k) {
      const int bits = static_cast<int>(rng() % 17);  // 0: a channel without bits
      b.max[k] = max_code(bits);
      b.written[k] = bits > 0 && rng() % 5 != 0;
    }
    const int n = 1 + static_cast<int>(rng() % 23), begin = static_cast<int>(rng() % 3) % n;
    std::vector<std::uint8_t> live(static_cast<std::size_t>(n));
    std::vector<std::uint16_t> src(4 * static_cast<std::size_t>(n)), dst(src.size());
    for (auto& l : live) l = rng() % 4 != 0;
    for (std::size_t i = 0; i < src.size(); ++i) {
      const std::uint32_t m = b.max[i % 4];
      // Codes of the channel's width, often at the ends of the range (the saturating cases).
      auto code = [&] { return static_cast<std::uint16_t>(rng() % 3 == 0 ? (rng() % 2 ? m : 0) : rng() % (m + 1)); };
      src[i] = code();
      dst[i] = code();
    }
    std::vector<std::uint16_t> want = dst, got = dst;
    const std::uint64_t a = blend_span_unit_factors_scalar(b, live.data(), src.data(), want.data(), begin, n);
    const std::uint64_t c = blend_span_unit_factors(b, live.data(), src.data(), got.data(), begin, n);
    ASSERT_EQ(a, c) << round;
    ASSERT_EQ(want, got) << round << " equation " << b.equation;
    blended += a;
  }
  EXPECT_GT(blended, 10000u);
  // One value worked by hand: REVERSE_SUBTRACT with ONE, ONE at 12 bits clamps 100 − 300 to 0.
  UnitFactorBlend rs;
  rs.equation = GL_FUNC_REVERSE_SUBTRACT;
  for (auto& m : rs.max) m = 4095;
  const std::uint8_t live2[2] = {1, 1};
  const std::uint16_t s2[8] = {300, 10, 4095, 0, 1, 2, 3, 4};
  std::uint16_t d2[8] = {100, 4095, 4095, 7, 0, 0, 0, 0};
  EXPECT_EQ(2u, blend_span_unit_factors(rs, live2, s2, d2, 0, 2));
  const std::uint16_t expect2[8] = {0, 4085, 0, 7, 0, 0, 0, 0};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(expect2[i], d2[i]) << i;
}

TEST(Blend, RealFactorSpanKernelEqualsTheScalarLoop) {
  // The AVX2 kernel against the scalar loop (the definition, §4.1.6 in reals): every factor
  // (and an invalid one, which counts as ZERO), every equation, source and destination widths
  // 0-16 apiece, products rounded or not, random constants, live fragments and written channels.
  std::mt19937 rng(23);
  const GLenum equations[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN, GL_MAX};
  const GLenum factors[] = {GL_ZERO, GL_ONE, GL_SRC_COLOR, GL_ONE_MINUS_SRC_COLOR, GL_DST_COLOR,
                            GL_ONE_MINUS_DST_COLOR, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_DST_ALPHA,
                            GL_ONE_MINUS_DST_ALPHA, GL_CONSTANT_COLOR, GL_ONE_MINUS_CONSTANT_COLOR,
                            GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA, GL_SRC_ALPHA_SATURATE, GL_TEXTURE_2D};
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uint64_t blended = 0;
  for (int round = 0; round < 6000; ++round) {
    RealBlend b;
    b.equation = equations[rng() % 5];
    b.src_factor = factors[rng() % 16];
    b.dst_factor = factors[rng() % 16];
    b.products_rounded = rng() % 3 == 0;
    const bool same = rng() % 2;
    for (int k = 0; k < 4; ++k) {
      b.constant[k] = rng() % 4 == 0 ? static_cast<double>(rng() % 2) : unit(rng);
      b.dst_bits[k] = static_cast<int>(rng() % 17);  // 0: a channel without bits (reads 1)
      b.src_bits[k] = same ? b.dst_bits[k] : static_cast<int>(rng() % 17);
      b.written[k] = b.dst_bits[k] > 0 && rng() % 5 != 0;
    }
    const int n = 1 + static_cast<int>(rng() % 19), begin = static_cast<int>(rng() % 3) % n;
    std::vector<std::uint8_t> live(static_cast<std::size_t>(n));
    std::vector<std::uint16_t> src(4 * static_cast<std::size_t>(n)), dst(src.size());
    for (auto& l : live) l = rng() % 4 != 0;
    for (std::size_t i = 0; i < src.size(); ++i) {
      auto code = [&](int bits) {
        const std::uint32_t m = max_code(bits);
        return static_cast<std::uint16_t>(rng() % 3 == 0 ? (rng() % 2 ? m : 0) : rng() % (m + 1));
      };
      src[i] = code(b.src_bits[i % 4]);
      dst[i] = code(b.dst_bits[i % 4]);
    }
    std::vector<std::uint16_t> want = dst, got = dst;
    const std::uint64_t a = blend_span_reals_scalar(b, live.data(), src.data(), want.data(), begin, n);
    const std::uint64_t c = blend_span_reals(b, live.data(), src.data(), got.data(), begin, n);
    ASSERT_EQ(a, c) << round;
    ASSERT_EQ(want, got) << round << " equation " << b.equation << " factors " << b.src_factor << " "
                         << b.dst_factor;
    blended += a;
  }
  EXPECT_GT(blended, 40000u);
  // Worked by hand: ONE_MINUS_DST_ALPHA, ONE at 8 bits (the final pass of the shadow-map
  // programs), destination alpha 51 (1 − 0.2 = 0.8), alpha not written:
  // red 100·0.8 + 50 = 130; green 255·0.8 + 255 clamps to 255; blue 0·0.8 + 7 = 7.
  RealBlend fin;
  fin.src_factor = GL_ONE_MINUS_DST_ALPHA;
  fin.dst_factor = GL_ONE;
  fin.written[3] = false;
  const std::uint8_t one_live[1] = {1};
  const std::uint16_t s1[4] = {100, 255, 0, 200};
  for (bool kernel : {false, true}) {
    std::uint16_t d1[4] = {50, 255, 7, 51};
    EXPECT_EQ(1u, kernel ? blend_span_reals(fin, one_live, s1, d1, 0, 1) : blend_span_reals_scalar(fin, one_live, s1, d1, 0, 1));
    const std::uint16_t expect1[4] = {130, 255, 7, 51};
    for (int k = 0; k < 4; ++k) EXPECT_EQ(expect1[k], d1[k]) << k << (kernel ? " kernel" : " scalar");
  }
}

TEST(Blend, ProductsRoundedOneByOneInTheMesaProfile) {
  // ADD with both factors 1/2 (alpha 128/255 would not be exact; use the constant alpha):
  // codes 101 and 51 at 8 bits. Exact: (101 + 51)/2 = 76 -> 76. Products rounded first:
  // 50.5 -> 51 and 25.5 -> 26 (ties up), 51 + 26 = 77.
  EXPECT_DOUBLE_EQ(blend_component(GL_FUNC_ADD, 101 / 255.0, 51 / 255.0, 0.5, 0.5) * 255.0, 76.0);
  EXPECT_DOUBLE_EQ(blend_component(GL_FUNC_ADD, 101 / 255.0, 51 / 255.0, 0.5, 0.5, 8) * 255.0, 77.0);
  for (const char* profile : {"ideal", "mesa-llvmpipe"}) {
    Context ctx(test::small_config(1, 1), *find_profile(profile));
    ctx.glClearColor(51 / 255.0f, 0, 0, 0);
    ctx.glClear(GL_COLOR_BUFFER_BIT);
    ctx.glEnable(GL_BLEND);
    ctx.glBlendColor(0, 0, 0, 0.5f);
    ctx.glBlendFunc(GL_CONSTANT_ALPHA, GL_CONSTANT_ALPHA);
    ctx.glColor4ub(101, 0, 0, 255);
    ctx.glRectf(-1, -1, 1, 1);
    EXPECT_EQ(test::pixel(ctx, 0, 0)[0], std::string(profile) == "ideal" ? 76u : 77u) << profile;
  }
}
