// Texturing with values computed by hand from §3.8 (and ARB/SGIX shadow).
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <optional>

#include <limits>

#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {

// One pixel (0,0) drawn by a quad whose four vertices all carry texture coordinate (s,t,r,q):
// the fragment's s/q, t/q, r/q are exactly those values.
void textured_pixel(Context& ctx, float s, float t, float r = 0, float q = 1) {
  ctx.glBegin(GL_QUADS);
  ctx.glTexCoord4f(s, t, r, q);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(1, 0);
  ctx.glVertex2f(1, 1);
  ctx.glVertex2f(0, 1);
  ctx.glEnd();
}


void luminance_1d(Context& ctx, GLenum filter, GLenum wrap) {
  const GLubyte ramp[4] = {0, 85, 170, 255};
  ctx.glTexImage1D(GL_TEXTURE_1D, 0, GL_LUMINANCE8, 4, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, ramp);
  ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
  ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
  ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
  const float white[4] = {1, 1, 1, 1};
  ctx.glTexParameterfv(GL_TEXTURE_1D, GL_TEXTURE_BORDER_COLOR, white);
  ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  ctx.glEnable(GL_TEXTURE_1D);
}

}  // namespace

TEST(Texture, LinearSamplingOfA2x2Texture) {
  // Texels (row 0 first): τ00 = 0, τ10 = 255, τ01 = 51, τ11 = 102 (LUMINANCE8).
  const GLubyte texels[4] = {0, 255, 51, 102};
  struct Case { float s, t; std::uint32_t code8, code12; };
  // (0.5, 0.5): α = β = 1/2: (0 + 1 + 0.2 + 0.4)/4 = 0.4 -> 102 / 1638.
  // (0.375, 0.625): u − ½ = 0.25, v − ½ = 0.75: 0.0625·1 + 0.5625·0.2 + 0.1875·0.4 = 0.25 -> 63.75 -> 64 / 1024.
  const Case cases[] = {{0.5f, 0.5f, 102, 1638}, {0.375f, 0.625f, 64, 1024}};
  for (int bits : {8, 12})
    for (const Case& c : cases) {
      Context ctx(test::small_config(1, 1, bits));
  test::window_projection(ctx);
      ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of 2 bytes, tightly packed
      ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE8, 2, 2, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, texels);
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
      ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
      ctx.glEnable(GL_TEXTURE_2D);
      textured_pixel(ctx, c.s, c.t);
      EXPECT_EQ(pixel(ctx, 0, 0)[0], bits == 8 ? c.code8 : c.code12) << c.s << "," << c.t << " bits " << bits;
      EXPECT_EQ(ctx.total_counters().texels_fetched, 4u);
    }
}

TEST(Texture, LinearFilterIn8_8FixedPointInTheMesaProfile) {
  // A29, by hand, on the 2×2 LUMINANCE8 texture above (τ00 = 0, τ10 = 255, τ01 = 51, τ11 = 102):
  // (0.5, 0.5): s·512 = 256, less 128: index 0, weight 128 (t alike).
  //   row 0: 0 + ⌊(128·255 + 128)/256⌋ = 128;  row 1: 51 + ⌊(128·51 + 128)/256⌋ = 51 + 26 = 77;
  //   rows: 128 + ⌊(128·(77 − 128) + 128)/256⌋ = 128 + ⌊−25⌋ = 103 — the spec's reals give 0.4 -> 102.
  // (0.5009765625, 0.5009765625): s·512 = 256.5, a tie, rounded to even: 256 — the same 103
  //   (rounded up, 257, the weight 129 would give 102).
  // A 12-bit framebuffer receives 103/255: 1654.06 -> 1654 (the spec's 0.4: 1638).
  // The filter applies to 8-bit components only: LUMINANCE12 (or a CLAMP wrap) keeps the spec's
  // arithmetic, 102.
  const GLubyte texels[4] = {0, 255, 51, 102};
  struct Case { float s, t; GLint internal; GLenum wrap; int bits; std::uint32_t code; };
  const Case cases[] = {{0.5f, 0.5f, GL_LUMINANCE8, GL_CLAMP_TO_EDGE, 8, 103},
                        {0.5009765625f, 0.5009765625f, GL_LUMINANCE8, GL_REPEAT, 8, 103},
                        {0.5f, 0.5f, GL_LUMINANCE8, GL_CLAMP_TO_EDGE, 12, 1654},
                        {0.5f, 0.5f, GL_LUMINANCE12, GL_CLAMP_TO_EDGE, 8, 102},
                        {0.5f, 0.5f, GL_LUMINANCE8, GL_CLAMP, 8, 102}};
  const MachineProfile* mesa = find_profile("mesa-llvmpipe");
  ASSERT_NE(mesa, nullptr);
  ASSERT_TRUE(mesa->arithmetic.texture_filter_8_8);
  for (const Case& c : cases) {
    Context ctx(test::small_config(1, 1, c.bits), *mesa);
    test::window_projection(ctx);
    ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    ctx.glTexImage2D(GL_TEXTURE_2D, 0, c.internal, 2, 2, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, texels);
    ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, static_cast<GLint>(c.wrap));
    ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, static_cast<GLint>(c.wrap));
    ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    ctx.glEnable(GL_TEXTURE_2D);
    textured_pixel(ctx, c.s, c.t);
    EXPECT_EQ(pixel(ctx, 0, 0)[0], c.code) << c.s << " format " << c.internal << " wrap " << c.wrap << " bits " << c.bits;
    EXPECT_EQ(ctx.total_counters().texels_fetched, 4u);
  }
}

TEST(Texture, WrapModesAtTheEdges) {
  // 1D LUMINANCE8 ramp {0, 85, 170, 255}, border colour 1. Values at s = 0 and s = 1 (8-bit codes):
  //  LINEAR REPEAT:        s=0: i0 = −1 -> 3 (1.0), i1 = 0 (0), α = ½ -> 0.5 -> 128; s=1 wraps to 0: 128.
  //  LINEAR CLAMP:         s=0: border (1) and 0 -> 128; s=1: u−½ = 3.5: texel 3 (1) and border (1) -> 255.
  //  LINEAR CLAMP_TO_EDGE: s clamped to 1/8 and 7/8: exactly texel 0 (0) and texel 3 (255).
  //  NEAREST CLAMP:        s=0 -> texel 0 (0); s=1 -> i = W − 1 = 3 (255).
  struct Case { GLenum filter, wrap; std::uint32_t at0, at1; };
  const Case cases[] = {{GL_LINEAR, GL_REPEAT, 128, 128},
                        {GL_LINEAR, GL_CLAMP, 128, 255},
                        {GL_LINEAR, GL_CLAMP_TO_EDGE, 0, 255},
                        {GL_NEAREST, GL_CLAMP, 0, 255},
                        {GL_NEAREST, GL_REPEAT, 0, 0}};
  for (const Case& c : cases)
    for (int end = 0; end < 2; ++end) {
      Context ctx(test::small_config(1, 1));
  test::window_projection(ctx);
      luminance_1d(ctx, c.filter, c.wrap);
      textured_pixel(ctx, static_cast<float>(end), 0);
      EXPECT_EQ(pixel(ctx, 0, 0)[0], end ? c.at1 : c.at0)
          << enum_name(c.filter) << " " << enum_name(c.wrap) << " s=" << end;
    }
}

TEST(Texture, ProjectiveTextureCoordinatesDivideByQ) {
  // Triangle (0,0), (4,0), (0,4) with (s, q) = (0, 1), (2, 2), (0, 1): at centre (1.5, 0.5)
  // the weights are 0.5, 0.375, 0.125, so s/q = (0.375·2)/(0.5 + 0.375·2 + 0.125) = 0.5454...
  // -> u = 2.18 -> texel 2 (170). Interpolating s/q itself would give 0.375 -> texel 1 (85).
  Context ctx(test::small_config(4, 4));
  test::window_projection(ctx);
  luminance_1d(ctx, GL_NEAREST, GL_CLAMP);
  ctx.glBegin(GL_TRIANGLES);
  ctx.glTexCoord4f(0, 0, 0, 1);
  ctx.glVertex2f(0, 0);
  ctx.glTexCoord4f(2, 0, 0, 2);
  ctx.glVertex2f(4, 0);
  ctx.glTexCoord4f(0, 0, 0, 1);
  ctx.glVertex2f(0, 4);
  ctx.glEnd();
  EXPECT_EQ(pixel(ctx, 1, 0)[0], 170u);
}

TEST(Texture, EyePlaneIsTransformedByTheModelviewAtTexGenTime) {
  // Plane (0,0,1,0) given under a translation (0,0,−2): p' = p·M⁻¹ = (0,0,1,2). Drawn with an
  // identity modelview at eye z = −1.25: s = −1.25 + 2 = 0.75 -> texel 3 (255) under CLAMP.
  // Using the draw-time modelview would give s = −1.25 -> clamped to 0 -> texel 0.
  Context ctx(test::small_config(1, 1));
  ctx.glMatrixMode(GL_PROJECTION);
  ctx.glOrtho(0, 1, 0, 1, -10, 10);
  ctx.glMatrixMode(GL_MODELVIEW);
  ctx.glTranslatef(0, 0, -2);
  const float plane[4] = {0, 0, 1, 0};
  ctx.glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_EYE_LINEAR);
  ctx.glTexGenfv(GL_S, GL_EYE_PLANE, plane);
  ctx.glLoadIdentity();
  ctx.glEnable(GL_TEXTURE_GEN_S);
  luminance_1d(ctx, GL_NEAREST, GL_CLAMP);
  ctx.glBegin(GL_QUADS);
  ctx.glVertex3f(0, 0, -1.25f);
  ctx.glVertex3f(1, 0, -1.25f);
  ctx.glVertex3f(1, 1, -1.25f);
  ctx.glVertex3f(0, 1, -1.25f);
  ctx.glEnd();
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 255u);
  EXPECT_EQ(ctx.total_counters().texgen_evaluations, 4u);
}

TEST(Texture, ObjectLinearTexgenWithTheTextureMatrix) {
  // s = x_object (plane (1,0,0,0)), then the texture matrix scales s by 1/4: at x = 2.5
  // (pixel 2's centre) s = 0.625 -> u = 2.5 -> NEAREST texel 2 (170).
  Context ctx(test::small_config(4, 1));
  test::window_projection(ctx);
  ctx.glTexGeni(GL_S, GL_TEXTURE_GEN_MODE, GL_OBJECT_LINEAR);
  ctx.glEnable(GL_TEXTURE_GEN_S);
  ctx.glMatrixMode(GL_TEXTURE);
  ctx.glScalef(0.25f, 1, 1);
  ctx.glMatrixMode(GL_MODELVIEW);
  luminance_1d(ctx, GL_NEAREST, GL_CLAMP);
  ctx.glBegin(GL_QUADS);
  ctx.glVertex2f(0, 0);
  ctx.glVertex2f(4, 0);
  ctx.glVertex2f(4, 1);
  ctx.glVertex2f(0, 1);
  ctx.glEnd();
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 0u);    // s = 0.125 -> u = 0.5
  EXPECT_EQ(pixel(ctx, 1, 0)[0], 85u);   // s = 0.375 -> u = 1.5
  EXPECT_EQ(pixel(ctx, 2, 0)[0], 170u);
  EXPECT_EQ(pixel(ctx, 3, 0)[0], 255u);
}

TEST(Texture, StorageKeepsTheInternalFormatWidth) {
  // A 12-bit value stored in RGBA8 loses its low bits: 0.3 -> 77 at 8 bits (76.5 in double ->
  // 77), read back into a 12-bit framebuffer as 77/255·4095 = 1236.53 -> 1237, not 1229.
  Context ctx(test::small_config(1, 1, 12));
  test::window_projection(ctx);
  const float texel[4] = {0.3f, 0.3f, 0.3f, 1.0f};
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_FLOAT, texel);
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  ctx.glEnable(GL_TEXTURE_2D);
  textured_pixel(ctx, 0.5f, 0.5f);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 1237u);
  GLint size = 0;
  ctx.glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_RED_SIZE, &size);
  EXPECT_EQ(size, 8);
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA12, 1, 1, 0, GL_RGBA, GL_FLOAT, texel);
  textured_pixel(ctx, 0.5f, 0.5f);
  // float(0.3)·4095 = 1228.50001 -> 1229 (float 0.3 is slightly above 0.3).
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 1229u);
}

TEST(Texture, EnvironmentModesForEachBaseFormat) {
  // Fragment colour Cf = (51, 102, 153, 204)/255 = (0.2, 0.4, 0.6, 0.8); env colour Cc =
  // (1, 0, 0.5, 0.25); texel components 0.5 (code 128/255 = 0.50196) unless noted.
  const double t = 128.0 / 255.0;
  const double cf[4] = {0.2, 0.4, 0.6, 0.8};
  const double cc[4] = {1.0, 0.0, 0.5, 0.25};
  struct Case {
    GLenum mode, base;
    double expect[4];  // by the spec's Tables 3.18-3.19
  };
  const Case cases[] = {
      {GL_REPLACE, GL_RGBA, {t, t, t, t}},
      {GL_REPLACE, GL_RGB, {t, t, t, cf[3]}},
      {GL_REPLACE, GL_ALPHA, {cf[0], cf[1], cf[2], t}},
      {GL_REPLACE, GL_LUMINANCE, {t, t, t, cf[3]}},
      {GL_REPLACE, GL_INTENSITY, {t, t, t, t}},
      {GL_MODULATE, GL_RGBA, {cf[0] * t, cf[1] * t, cf[2] * t, cf[3] * t}},
      {GL_MODULATE, GL_LUMINANCE, {cf[0] * t, cf[1] * t, cf[2] * t, cf[3]}},
      {GL_MODULATE, GL_ALPHA, {cf[0], cf[1], cf[2], cf[3] * t}},
      {GL_DECAL, GL_RGB, {t, t, t, cf[3]}},
      {GL_DECAL, GL_RGBA, {cf[0] * (1 - t) + t * t, cf[1] * (1 - t) + t * t, cf[2] * (1 - t) + t * t, cf[3]}},
      {GL_DECAL, GL_LUMINANCE, {cf[0], cf[1], cf[2], cf[3]}},  // undefined in GL: unchanged (A12)
      {GL_BLEND, GL_RGB, {cf[0] * (1 - t) + cc[0] * t, cf[1] * (1 - t) + cc[1] * t, cf[2] * (1 - t) + cc[2] * t, cf[3]}},
      {GL_BLEND, GL_INTENSITY,
       {cf[0] * (1 - t) + cc[0] * t, cf[1] * (1 - t) + cc[1] * t, cf[2] * (1 - t) + cc[2] * t, cf[3] * (1 - t) + cc[3] * t}},
      {GL_BLEND, GL_RGBA, {cf[0] * (1 - t) + cc[0] * t, cf[1] * (1 - t) + cc[1] * t, cf[2] * (1 - t) + cc[2] * t, cf[3] * t}},
      {GL_ADD, GL_RGBA, {cf[0] + t, cf[1] + t, 1.0, cf[3] * t}},
      {GL_ADD, GL_INTENSITY, {cf[0] + t, cf[1] + t, 1.0, 1.0}},
  };
  for (const Case& c : cases) {
    Context ctx(test::small_config(1, 1, 8));
  test::window_projection(ctx);
    const GLubyte texel[4] = {128, 128, 128, 128};
    GLenum format = GL_RGBA;
    GLint internal = GL_RGBA8;
    switch (c.base) {
      case GL_RGB: format = GL_RGB; internal = GL_RGB8; break;
      case GL_ALPHA: format = GL_ALPHA; internal = GL_ALPHA8; break;
      case GL_LUMINANCE: format = GL_LUMINANCE; internal = GL_LUMINANCE8; break;
      case GL_INTENSITY: format = GL_LUMINANCE; internal = GL_INTENSITY8; break;
      default: break;
    }
    ctx.glTexImage2D(GL_TEXTURE_2D, 0, internal, 1, 1, 0, format, GL_UNSIGNED_BYTE, texel);
    ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    const float env[4] = {1.0f, 0.0f, 0.5f, 0.25f};
    ctx.glTexEnvfv(GL_TEXTURE_ENV, GL_TEXTURE_ENV_COLOR, env);
    ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, static_cast<GLint>(c.mode));
    ctx.glEnable(GL_TEXTURE_2D);
    ctx.glColor4ub(51, 102, 153, 204);
    textured_pixel(ctx, 0.5f, 0.5f);
    const auto p = pixel(ctx, 0, 0);
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(p[k], static_cast<std::uint32_t>(std::floor(std::min(1.0, c.expect[k]) * 255.0 + 0.5)))
          << enum_name(c.mode) << " " << enum_name(c.base) << " component " << k;
  }
}

TEST(Texture, DepthCompareNearestAndLinear) {
  // DEPTH_COMPONENT16 2x1 texture: texels 0.25 and 0.75. r = 0.5, sampled half-way (LINEAR):
  // ARB LEQUAL (r <= D): texel 0 fails (0), texel 1 passes (1) -> 0.5 -> 128.
  // NEAREST at s = 0.25 (texel 0): fails -> 0; at s = 0.75 (texel 1): passes -> 255.
  // SGIX LEQUAL_R (texel <= r): the opposite results.
  const GLushort depth[2] = {16384, 49151};  // 0.25 and 0.75 at 16 bits (rounded)
  auto run = [&](GLenum filter, bool sgix, float s) {
    Context ctx(test::small_config(1, 1, 8));
  test::window_projection(ctx);
    ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT16, 2, 1, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, depth);
    ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
    ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
    ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    if (sgix) {
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_SGIX, GL_TRUE);
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_OPERATOR_SGIX, GL_TEXTURE_LEQUAL_R_SGIX);
    } else {
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_R_TO_TEXTURE);
      ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    }
    ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    ctx.glEnable(GL_TEXTURE_2D);
    textured_pixel(ctx, s, 0.5f, 0.5f);
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return pixel(ctx, 0, 0)[0];
  };
  EXPECT_EQ(run(GL_LINEAR, false, 0.5f), 128u);
  EXPECT_EQ(run(GL_NEAREST, false, 0.25f), 0u);
  EXPECT_EQ(run(GL_NEAREST, false, 0.75f), 255u);
  EXPECT_EQ(run(GL_LINEAR, true, 0.5f), 128u);
  EXPECT_EQ(run(GL_NEAREST, true, 0.25f), 255u);
  EXPECT_EQ(run(GL_NEAREST, true, 0.75f), 0u);
}

TEST(Texture, CopyTexImageFromTheFramebufferAndDepthPlane) {
  // Colour: a 12-bit framebuffer copied into RGBA8 keeps 8 bits; depth into DEPTH_COMPONENT16.
  FramebufferConfig cfg = test::small_config(2, 2, 12);
  Context ctx(cfg);
  ctx.glClearColor(0.3f, 0.0f, 0.0f, 1.0f);  // float 0.3 -> 1229 at 12 bits
  ctx.glClearDepth(0.25);                    // 0.25·(2^24 − 1) -> 4194304
  ctx.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  ctx.glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 0, 0, 2, 2, 0);
  GLubyte rgba[16];
  ctx.glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
  EXPECT_EQ(rgba[0], 77u);  // 1229/4095·255 = 76.53 -> 77
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ctx.glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT16, 0, 0, 2, 2, 0);
  GLushort d[4];
  ctx.glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, d);
  EXPECT_EQ(d[3], 16384u);  // 4194304/16777215·65535 = 16383.75 -> 16384
}

TEST(Texture, CopyTexImageReplacesEveryTexelOfALevelThatHeldOthers) {
  // glCopyTexImage2D redefines the level: whatever it held before is gone. A 4x32 level of
  // 200s is replaced by a copy of a 4x32 rectangle partly outside the 4x20 window of 100s:
  // the pixels inside give 100, those outside 0 (passim reads pixels outside the window as
  // 0, docs/arithmetic.md). On one thread and on two (where the copy runs in bands of 16 rows
  // on the lanes), and under a histogram sink, which consumes the pixels: the level is then 0.
  for (int threads : {1, 2}) {
    for (bool sink : {false, true}) {
      Context ctx(test::small_config(4, 20, 8));
      ctx.set_threads(threads);
      std::vector<GLubyte> old(4 * 4 * 32, 200);
      ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 4, 32, 0, GL_RGBA, GL_UNSIGNED_BYTE, old.data());
      ctx.glClearColor(100.0f / 255.0f, 100.0f / 255.0f, 100.0f / 255.0f, 100.0f / 255.0f);
      ctx.glClear(GL_COLOR_BUFFER_BIT);
      if (sink) {
        ctx.glHistogram(GL_HISTOGRAM, 16, GL_RGBA, GL_TRUE);
        ctx.glEnable(GL_HISTOGRAM);
      }
      ctx.glCopyTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 0, 0, 4, 32, 0);
      ASSERT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
      GLubyte texels[4 * 4 * 32];
      ctx.glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
      for (int i = 0; i < 4 * 4 * 32; ++i) {
        const bool inside = i < 4 * 4 * 20;  // rows 0 to 19
        EXPECT_EQ(texels[i], sink ? 0u : (inside ? 100u : 0u)) << threads << " " << sink << " " << i;
      }
    }
  }
}

TEST(Texture, ErrorsAndIncompleteTextures) {
  Context ctx(test::small_config(1, 1));
  test::window_projection(ctx);
  const GLubyte texel[4] = {0, 0, 0, 0};
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 3, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);  // 3 is not 2^k
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, 0x1234, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 2, GL_RGBA, GL_UNSIGNED_BYTE, texel);  // border 2
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_COLOR_INDEX, GL_UNSIGNED_BYTE, texel);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 131072, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);  // > 65536
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_VALUE));
  // Within MAX_TEXTURE_SIZE on each side but 2^25 texels, over the 2^24 budget: §2.5's
  // OUT_OF_MEMORY, and the texture keeps no level.
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 65536, 512, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_OUT_OF_MEMORY));
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT16, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, texel);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  ctx.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, texel);  // level undefined
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_REPEAT);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_LINEAR);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glTexGeni(GL_R, GL_TEXTURE_GEN_MODE, GL_SPHERE_MAP);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM));
  ctx.glBindTexture(GL_TEXTURE_2D, 5);
  ctx.glBindTexture(GL_TEXTURE_1D, 5);  // 5 is a 2D texture now
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_OPERATION));
  // An incomplete texture (default MIN_FILTER needs mipmaps) disables texturing: the
  // fragment keeps its colour.
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 2, 2, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  ctx.glEnable(GL_TEXTURE_2D);
  ctx.glColor3f(1, 1, 1);
  textured_pixel(ctx, 0.5f, 0.5f);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 255u);
  EXPECT_EQ(ctx.total_counters().texture_lookups, 0u);
}

TEST(Texture, MipmapLevelSelection) {
  // 4x4 base level white (255), 2x2 level grey 128, 1x1 level black: a quad of 1x1 pixels
  // mapped to the whole texture has ρ = 4 (λ = 2) -> NEAREST_MIPMAP_NEAREST picks level
  // ceil(0 + 2 + ½) − 1 = 2 (black); a 4x4 quad has λ = 0 -> level 0 (white).
  Context ctx(test::small_config(4, 4));
  test::window_projection(ctx);
  std::vector<GLubyte> l0(16, 255), l1(4, 128), l2(1, 0);
  ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE8, 4, 4, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, l0.data());
  ctx.glTexImage2D(GL_TEXTURE_2D, 1, GL_LUMINANCE8, 2, 2, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, l1.data());
  ctx.glTexImage2D(GL_TEXTURE_2D, 2, GL_LUMINANCE8, 1, 1, 0, GL_LUMINANCE, GL_UNSIGNED_BYTE, l2.data());
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  ctx.glEnable(GL_TEXTURE_2D);
  auto quad = [&](float size) {
    ctx.glBegin(GL_QUADS);
    ctx.glTexCoord2f(0, 0);
    ctx.glVertex2f(0, 0);
    ctx.glTexCoord2f(1, 0);
    ctx.glVertex2f(size, 0);
    ctx.glTexCoord2f(1, 1);
    ctx.glVertex2f(size, size);
    ctx.glTexCoord2f(0, 1);
    ctx.glVertex2f(0, size);
    ctx.glEnd();
  };
  quad(4);
  EXPECT_EQ(pixel(ctx, 2, 2)[0], 255u);
  quad(1);
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 0u);
  ctx.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  quad(2);  // λ = 1: exactly level 1 (weight 0 on level 2) -> 128
  EXPECT_EQ(pixel(ctx, 0, 0)[0], 128u);
}

TEST(Fog, LinearExpExp2) {
  // White fragments at eye z = −1 (c = 1) or −2 (c = 2), fog colour black:
  //  LINEAR start 0, end 4, c = 1: f = 3/4 -> 191.25 -> 191 (8 bits), 3071.25 -> 3071 (12 bits).
  //  EXP density 0.5, c = 2: f = e^−1 = 0.367879 -> 93.81 -> 94; 0.367879·4095 = 1506.47 -> 1506.
  //  EXP2 density 0.5, c = 1: f = e^−0.25 = 0.778801 -> 198.59 -> 199; 3189.19 -> 3189.
  struct Case { GLenum mode; float z; std::uint32_t c8, c12; };
  const Case cases[] = {{GL_LINEAR, -1, 191, 3071}, {GL_EXP, -2, 94, 1506}, {GL_EXP2, -1, 199, 3189}};
  for (const Case& c : cases)
    for (int bits : {8, 12}) {
      Context ctx(test::small_config(1, 1, bits));
      ctx.glMatrixMode(GL_PROJECTION);
      ctx.glOrtho(0, 1, 0, 1, -10, 10);
      ctx.glMatrixMode(GL_MODELVIEW);
      ctx.glEnable(GL_FOG);
      ctx.glFogi(GL_FOG_MODE, static_cast<GLint>(c.mode));
      ctx.glFogf(GL_FOG_START, 0);
      ctx.glFogf(GL_FOG_END, 4);
      ctx.glFogf(GL_FOG_DENSITY, 0.5f);
      ctx.glColor4f(1, 1, 1, 1);
      ctx.glBegin(GL_QUADS);
      ctx.glVertex3f(0, 0, c.z);
      ctx.glVertex3f(1, 0, c.z);
      ctx.glVertex3f(1, 1, c.z);
      ctx.glVertex3f(0, 1, c.z);
      ctx.glEnd();
      const auto p = pixel(ctx, 0, 0);
      EXPECT_EQ(p[0], bits == 8 ? c.c8 : c.c12) << enum_name(c.mode) << " bits " << bits;
      EXPECT_EQ(p[3], bits == 8 ? 255u : 4095u);  // alpha unchanged
      EXPECT_EQ(ctx.total_counters().fog_operations, 1u);
    }
}

#include <random>

#include "stages/texture_stage.hpp"
#include "stages/kernel_paths.hpp"

TEST(TextureFastPath, NearestAndLinearReplaceMatchTheGeneralPath) {
  // Random textured triangles (projective coordinates, every wrap mode, borders, 1D and 2D,
  // every base format, widths 4-16, fragment widths 5/8/12): planes and counters must be
  // identical with and without the NEAREST/REPLACE and LINEAR/REPLACE fast paths.
  const GLenum formats[] = {GL_ALPHA8, GL_LUMINANCE12, GL_LUMINANCE4_ALPHA4, GL_INTENSITY16, GL_RGB5, GL_RGBA12, GL_RGB10_A2};
  const GLenum wraps[] = {GL_REPEAT, GL_CLAMP, GL_CLAMP_TO_EDGE};
  auto draw = [&](Context& ctx, unsigned seed, GLenum filter) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-4.0f, 36.0f), st(-1.5f, 2.5f), q(0.3f, 2.0f), c(0.0f, 1.0f);
    test::window_projection(ctx);
    ctx.glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    const int dims = 1 + static_cast<int>(rng() % 2), border = static_cast<int>(rng() % 2);
    const GLenum target = dims == 1 ? GL_TEXTURE_1D : GL_TEXTURE_2D;
    const int w = 4 << (rng() % 3), h = dims == 1 ? 1 : 2 << (rng() % 3);
    std::vector<float> texels(static_cast<std::size_t>((w + 2 * border) * (h + (dims == 2 ? 2 * border : 0)) * 4));
    for (float& v : texels) v = c(rng);
    const GLenum format = formats[rng() % 7];
    if (dims == 1)
      ctx.glTexImage1D(target, 0, static_cast<GLint>(format), w + 2 * border, border, GL_RGBA, GL_FLOAT, texels.data());
    else
      ctx.glTexImage2D(target, 0, static_cast<GLint>(format), w + 2 * border, h + 2 * border, border, GL_RGBA, GL_FLOAT,
                       texels.data());
    ctx.glTexParameteri(target, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
    ctx.glTexParameteri(target, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
    ctx.glTexParameteri(target, GL_TEXTURE_WRAP_S, static_cast<GLint>(wraps[rng() % 3]));
    ctx.glTexParameteri(target, GL_TEXTURE_WRAP_T, static_cast<GLint>(wraps[rng() % 3]));
    const GLfloat border_color[4] = {c(rng), c(rng), c(rng), c(rng)};
    ctx.glTexParameterfv(target, GL_TEXTURE_BORDER_COLOR, border_color);
    ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, rng() % 4 ? GL_REPLACE : GL_MODULATE);
    ctx.glEnable(target);
    for (int k = 0; k < 30; ++k) {
      ctx.glBegin(GL_TRIANGLES);
      for (int v = 0; v < 3; ++v) {
        ctx.glColor4f(c(rng), c(rng), c(rng), c(rng));
        const float qq = q(rng);
        ctx.glTexCoord4f(st(rng) * qq, st(rng) * qq, 0.0f, qq);
        ctx.glVertex3f(pos(rng), pos(rng), 0.0f);
      }
      ctx.glEnd();
    }
  };
  std::optional<ScopedKernelPaths> paths;  // the general paths for the second drawing
  for (GLenum filter : {GL_NEAREST, GL_LINEAR}) {
    TextureStage::reset_fast_path_fragments_here();
    for (int bits : {5, 8, 12}) {
      for (unsigned seed = 1; seed <= 40; ++seed) {
        Context fast(test::small_config(32, 32, bits)), general(test::small_config(32, 32, bits));
        draw(fast, seed, filter);
        paths.emplace(KernelPaths{KernelPaths::Simd::Avx2, false});
        draw(general, seed, filter);
        paths.reset();
        ASSERT_EQ(fast.framebuffer().color[0].rgba, general.framebuffer().color[0].rgba)
            << enum_name(filter) << " " << bits << " " << seed;
        ASSERT_TRUE(fast.total_counters() == general.total_counters()) << enum_name(filter) << " " << bits << " " << seed;
        ASSERT_EQ(fast.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
      }
    }
    EXPECT_GT(TextureStage::fast_path_fragments_here(), 10000u) << enum_name(filter);  // the fast path did run
  }
}

TEST(TextureBorders, OneDimensionalTextureWithABorderSamplesItsTexels) {
  // A 1D LUMINANCE8 texture of 4 texels with a border: stored 10 | 20 30 40 50 | 60, border
  // colour white. NEAREST at s = 0.6: texel ⌊0.6·4⌋ = 2 -> 40. LINEAR at s = 0 under CLAMP:
  // u − ½ = −0.5, so ½ of the left border texel and ½ of texel 0: (10 + 20)/2 = 15.
  // (Until this test the border made every lookup return the border colour.)
  for (GLenum filter : {GL_NEAREST, GL_LINEAR}) {
    Context ctx(test::small_config(1, 1));
    test::window_projection(ctx);
    const GLubyte texels[6] = {10, 20, 30, 40, 50, 60};
    ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    ctx.glTexImage1D(GL_TEXTURE_1D, 0, GL_LUMINANCE8, 6, 1, GL_LUMINANCE, GL_UNSIGNED_BYTE, texels);
    ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
    ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(filter));
    ctx.glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP);
    const GLfloat white[4] = {1, 1, 1, 1};
    ctx.glTexParameterfv(GL_TEXTURE_1D, GL_TEXTURE_BORDER_COLOR, white);
    ctx.glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
    ctx.glEnable(GL_TEXTURE_1D);
    ctx.glTexCoord1f(filter == GL_NEAREST ? 0.6f : 0.0f);
    ctx.glRectf(0, 0, 1, 1);
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    EXPECT_EQ(pixel(ctx, 0, 0)[0], filter == GL_NEAREST ? 40u : 15u) << enum_name(filter);
  }
}

// Found by fuzzing: an enum given as a negative float (glTexParameterf(..., −9728)) was an
// undefined conversion; it is GL_INVALID_ENUM, and a huge level saturates.
TEST(TextureParameters, FloatEnumsOutOfRangeAreInvalidEnum) {
  Context ctx(test::small_config(4, 4));
  for (float bad : {-9728.0f, 9728.5f, 1e30f, std::numeric_limits<float>::quiet_NaN()}) {
    ctx.glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, bad);
    EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_INVALID_ENUM)) << bad;
  }
  ctx.glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, static_cast<float>(GL_LINEAR));
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  ctx.glTexParameterf(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 1e30f);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  GLint level = 0;
  ctx.glGetTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, &level);
  EXPECT_EQ(level, 2147483647);
}

// Issue 21's bar for the memory budget: four 4096² RGBA8 textures, loaded with data, fit in
// the default 1 GiB beside an 800x600 framebuffer — texels are kept as 16-bit codes (8 bytes
// a texel: 4 × 128 MiB) and the load's scratch is released between loads. The process's
// peak resident size stays under the budget too (each test is its own process in ctest).
TEST(Texture, FourLargeRgba8TexturesFitTheDefaultBudget) {
  Context ctx{FramebufferConfig{}};
  constexpr int kSide = 4096;
  std::vector<GLubyte> image(4u * kSide * kSide);
  for (std::size_t i = 0; i < image.size(); ++i) image[i] = static_cast<GLubyte>(i * 7 + i / 4096);
  GLuint names[4];
  ctx.glGenTextures(4, names);
  for (GLuint name : names) {
    ctx.glBindTexture(GL_TEXTURE_2D, name);
    ctx.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, kSide, kSide, 0, GL_RGBA, GL_UNSIGNED_BYTE, image.data());
    ASSERT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << "texture " << name;
  }
  // The last texture's texels read back as given (a spot check of the codes).
  std::vector<GLubyte> back(image.size());
  ctx.glGetTexImage(GL_TEXTURE_2D, 0, GL_RGBA, GL_UNSIGNED_BYTE, back.data());
  EXPECT_TRUE(back == image);
#if !defined(__SANITIZE_ADDRESS__)  // (AddressSanitizer's shadow and quarantine are not passim's)
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  EXPECT_LT(static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u, std::uint64_t{1} << 30) << "peak resident size";
#endif
}
