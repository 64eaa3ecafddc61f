// Lighting of known vertices (§2.13.1), computed by hand.
#include <gtest/gtest.h>

#include "test_util.hpp"

using namespace passim;
using passim::test::pixel;

namespace {
// Draws one lit point at the origin (eye = object coordinates) into pixel (1,1) of a 3x3 window.
void lit_point(Context& ctx) {
  ctx.glMatrixMode(GL_PROJECTION);
  ctx.glLoadIdentity();
  ctx.glOrtho(-1.5, 1.5, -1.5, 1.5, -1, 1);
  ctx.glMatrixMode(GL_MODELVIEW);
  ctx.glLoadIdentity();
  ctx.glEnable(GL_LIGHTING);
  ctx.glEnable(GL_LIGHT0);
  ctx.glNormal3f(0, 0, 1);
  ctx.glBegin(GL_POINTS);
  ctx.glVertex3f(0, 0, 0);
  ctx.glEnd();
}
}  // namespace

TEST(Lighting, DirectionalDiffuseWithDefaults) {
  // Defaults: material ambient 0.2, diffuse 0.8, specular 0; model ambient 0.2; LIGHT0
  // diffuse 1 at (0,0,1,0). c = 0.2·0.2 + 1·0.8·1 = 0.84: 214.2 -> 214 (8 bits),
  // 3439.8 -> 3440 (12 bits); alpha = diffuse alpha 1.
  Context c8(test::small_config(3, 3, 8));
  Context c12(test::small_config(3, 3, 12));
  lit_point(c8);
  lit_point(c12);
  EXPECT_EQ(pixel(c8, 1, 1), (std::array<std::uint32_t, 4>{214, 214, 214, 255}));
  EXPECT_EQ(pixel(c12, 1, 1), (std::array<std::uint32_t, 4>{3440, 3440, 3440, 4095}));
}

TEST(Lighting, PositionalLightAttenuationAndSpecular) {
  // Light at (3,0,4): distance 5, VP = (0.6, 0, 0.8), n·VP = 0.8; attenuation
  // 1/(1 + 0.1·5) = 2/3. Light ambient 0.1 (material ambient 0.2): 0.02. Diffuse
  // material 0.5: 0.4. h = VP + (0,0,1) = (0.6, 0, 1.8), n·ĥ = 1.8/sqrt(3.6), (n·ĥ)^2 = 0.9,
  // shininess 10: 0.9^5 = 0.59049, material and light specular 1.
  // c = 0.2·0.2 + (2/3)(0.02 + 0.4 + 0.59049) = 0.04 + 0.67366 = 0.71366:
  // 181.98 -> 182 (8 bits), 2922.44 -> 2922 (12 bits).
  for (int bits : {8, 12}) {
    Context ctx(test::small_config(3, 3, bits));
    const float pos[4] = {3, 0, 4, 1};
    const float amb[4] = {0.1f, 0.1f, 0.1f, 1};
    const float diff[4] = {0.5f, 0.5f, 0.5f, 1};
    const float spec[4] = {1, 1, 1, 1};
    ctx.glLightfv(GL_LIGHT0, GL_POSITION, pos);
    ctx.glLightfv(GL_LIGHT0, GL_AMBIENT, amb);
    ctx.glLightf(GL_LIGHT0, GL_LINEAR_ATTENUATION, 0.1f);
    ctx.glMaterialfv(GL_FRONT, GL_DIFFUSE, diff);
    ctx.glMaterialfv(GL_FRONT, GL_SPECULAR, spec);
    ctx.glMaterialf(GL_FRONT, GL_SHININESS, 10);
    lit_point(ctx);
    const std::uint32_t expected = bits == 8 ? 182u : 2922u;
    EXPECT_EQ(pixel(ctx, 1, 1)[0], expected) << bits;
    EXPECT_EQ(pixel(ctx, 1, 1)[2], expected) << bits;
  }
}

TEST(Lighting, LightPositionUsesModelviewAtCallTime) {
  // The light is placed with a translation (0,0,5) on the modelview, then the modelview is
  // reset: the light stays at eye (0,0,5), straight above the point: n·VP = 1, as in the first test.
  Context ctx(test::small_config(3, 3, 8));
  ctx.glTranslatef(0, 0, 5);
  const float pos[4] = {0, 0, 0, 1};
  ctx.glLightfv(GL_LIGHT0, GL_POSITION, pos);
  lit_point(ctx);
  EXPECT_EQ(pixel(ctx, 1, 1)[0], 214u);
}

TEST(Lighting, ColorMaterialTracksCurrentColour) {
  // COLOR_MATERIAL (AMBIENT_AND_DIFFUSE) with colour (0.5, 0.25, 1): c = 0.2·a + 1·d = 1.2·colour,
  // clamped: (0.6, 0.3, 1.2 -> 1): 153, 76.5 -> 77, 255.
  Context ctx(test::small_config(3, 3, 8));
  ctx.glEnable(GL_COLOR_MATERIAL);
  ctx.glColor3f(0.5f, 0.25f, 1.0f);
  lit_point(ctx);
  EXPECT_EQ(pixel(ctx, 1, 1), (std::array<std::uint32_t, 4>{153, 77, 255, 255}));
}
