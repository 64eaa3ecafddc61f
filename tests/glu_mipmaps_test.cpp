// The gluBuild1DMipmaps / gluBuild2DMipmaps helper (docs/arithmetic.md A28): levels
// computed by hand from SGI GLU 1.3's halving rules.
#include <gtest/gtest.h>

#include <cmath>

#include <sstream>

#include "trace_io/trace.hpp"
#include "client/glu_mipmaps.hpp"
#include "test_util.hpp"

using namespace passim;

namespace {

std::vector<GLubyte> level_bytes(Context& ctx, GLenum target, int level, int count) {
  std::vector<GLubyte> out(static_cast<std::size_t>(count), 0);
  ctx.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  ctx.glGetTexImage(target, level, GL_LUMINANCE, GL_UNSIGNED_BYTE, out.data());
  return out;
}

TEST(GluMipmaps, TwoDimensionalUnsignedBytesHalveByBoxThenPair) {
  // 4x2 luminance, rows bottom first, read with UNPACK_ALIGNMENT 1 and ROW_LENGTH 5 (one
  // unused byte per row). Level 1 (2x1): (10+20+50+60+2)/4 = 142/4 = 35,
  // (30+41+70+80+2)/4 = 223/4 = 55. Level 2 (1x1, a pair): (35+55)/2 = 45.
  Context ctx(test::small_config(4, 4));
  const GLubyte image[10] = {10, 20, 30, 41, 99, 50, 60, 70, 80, 99};
  ctx.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  ctx.glPixelStorei(GL_UNPACK_ROW_LENGTH, 5);
  EXPECT_EQ(ctx.gluBuild2DMipmaps(GL_TEXTURE_2D, GL_LUMINANCE8, 4, 2, GL_LUMINANCE, GL_UNSIGNED_BYTE, image), 0);
  EXPECT_EQ(ctx.glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  EXPECT_EQ(level_bytes(ctx, GL_TEXTURE_2D, 0, 8), (std::vector<GLubyte>{10, 20, 30, 41, 50, 60, 70, 80}));
  EXPECT_EQ(level_bytes(ctx, GL_TEXTURE_2D, 1, 2), (std::vector<GLubyte>{35, 55}));
  EXPECT_EQ(level_bytes(ctx, GL_TEXTURE_2D, 2, 1), (std::vector<GLubyte>{45}));
  GLint width = -1;
  ctx.glGetTexLevelParameteriv(GL_TEXTURE_2D, 3, GL_TEXTURE_WIDTH, &width);
  EXPECT_EQ(width, 0);  // no level past 1x1
  // The application's unpack modes are as it left them.
  GLint alignment = 0, row_length = 0;
  ctx.glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
  ctx.glGetIntegerv(GL_UNPACK_ROW_LENGTH, &row_length);
  EXPECT_EQ(alignment, 1);
  EXPECT_EQ(row_length, 5);
}

TEST(GluMipmaps, OneDimensionalHalvesByPairs) {
  // 4 texels 7, 8, 100, 201: level 1 (7+8)/2 = 7, (100+201)/2 = 150; level 2 (7+150)/2 = 78.
  Context ctx(test::small_config(4, 4));
  const GLubyte image[4] = {7, 8, 100, 201};
  EXPECT_EQ(ctx.gluBuild1DMipmaps(GL_TEXTURE_1D, GL_LUMINANCE8, 4, GL_LUMINANCE, GL_UNSIGNED_BYTE, image), 0);
  EXPECT_EQ(level_bytes(ctx, GL_TEXTURE_1D, 1, 2), (std::vector<GLubyte>{7, 150}));
  EXPECT_EQ(level_bytes(ctx, GL_TEXTURE_1D, 2, 1), (std::vector<GLubyte>{78}));
}

TEST(GluMipmaps, HalvingRulesPerType) {
  // Box and pair of each type, by hand from the rules in client/glu_mipmaps.hpp.
  const std::vector<double> box = {-5, -4, 3, 1};  // 2x2, one component
  EXPECT_EQ(glu_halve_image(box, 2, 2, 1, GL_BYTE)[0], 0.0);    // (-5 + 2)/4 = -3/4 -> 0 (toward zero)
  EXPECT_EQ(glu_halve_image(box, 2, 2, 1, GL_SHORT)[0], 0.0);
  EXPECT_EQ(glu_halve_image(box, 2, 2, 1, GL_INT)[0], 0.0);     // -5/4 + 0.5 = -0.75 -> 0
  EXPECT_EQ(glu_halve_image(box, 2, 2, 1, GL_FLOAT)[0], -1.25);  // -5/4
  const std::vector<double> pair = {-3, -2};                     // 2x1
  EXPECT_EQ(glu_halve_image(pair, 2, 1, 1, GL_BYTE)[0], -2.0);    // -5/2 -> -2
  // INT pairs are read as unsigned: (4294967293 + 4294967294)/2 = 4294967293.5 is past
  // INT_MAX; its conversion gives INT_MIN on x86 (kept, as the sample implementation ran).
  EXPECT_EQ(glu_halve_image(pair, 2, 1, 1, GL_INT)[0], -2147483648.0);
  EXPECT_EQ(glu_halve_image({4294967295.0, 4294967295.0, 4294967295.0, 4294967294.0}, 2, 2, 1, GL_UNSIGNED_INT)[0],
            4294967295.0);  // 4294967294.75 + 0.5, truncated
  EXPECT_EQ(glu_halve_image({1, 2, 3, 4}, 1, 4, 1, GL_UNSIGNED_SHORT), (std::vector<double>{1, 3}));  // a column of pairs
  // Float box sums in float: 1 + 2^-24 + 2^-24 rounds to 1 twice, then + 1 = 2, /4 = 0.5.
  const double tiny = std::ldexp(1.0, -24);
  EXPECT_EQ(glu_halve_image({1.0, tiny, tiny, 1.0}, 2, 2, 1, GL_FLOAT)[0], 0.5);
}

TEST(GluMipmaps, BadInputReturnsTheGluErrorAndSpecifiesNothing) {
  Context ctx(test::small_config(4, 4));
  const GLubyte image[12] = {};
  EXPECT_EQ(ctx.gluBuild2DMipmaps(GL_TEXTURE_2D, GL_LUMINANCE8, 3, 4, GL_LUMINANCE, GL_UNSIGNED_BYTE, image), 100901);
  EXPECT_EQ(ctx.gluBuild2DMipmaps(GL_TEXTURE_2D, GL_LUMINANCE8, 0, 4, GL_LUMINANCE, GL_UNSIGNED_BYTE, image), 100901);
  EXPECT_EQ(ctx.gluBuild2DMipmaps(GL_TEXTURE_2D, GL_LUMINANCE8, 2, 2, GL_LUMINANCE, GL_UNSIGNED_SHORT_5_6_5, image),
            100900);
  EXPECT_EQ(ctx.gluBuild2DMipmaps(GL_TEXTURE_1D, GL_LUMINANCE8, 2, 2, GL_LUMINANCE, GL_UNSIGNED_BYTE, image), 100900);
  GLint width = -1;
  ctx.glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &width);
  EXPECT_EQ(width, 0);
  EXPECT_FALSE(ctx.warnings().empty());
}

TEST(GluMipmaps, ImagesLargerThanTheLimitLoseTheirTopLevels) {
  // The ideal profile's limit is large; a context with a 4-texel limit is made from a profile copy.
  MachineProfile profile = *find_profile("ideal");
  profile.limits.max_texture_size = 2;
  Context ctx(test::small_config(4, 4), profile);
  const GLubyte image[4] = {0, 4, 8, 12};  // 4 texels: level 0 is (0+4)/2, (8+12)/2 = 2, 10
  EXPECT_EQ(ctx.gluBuild1DMipmaps(GL_TEXTURE_1D, GL_LUMINANCE8, 4, GL_LUMINANCE, GL_UNSIGNED_BYTE, image), 0);
  EXPECT_EQ(level_bytes(ctx, GL_TEXTURE_1D, 0, 2), (std::vector<GLubyte>{2, 10}));
  EXPECT_EQ(level_bytes(ctx, GL_TEXTURE_1D, 1, 1), (std::vector<GLubyte>{6}));
}

TEST(GluMipmaps, RecordedCallReplaysToTheSameLevels) {
  Context original(test::small_config(4, 4));
  test::Recording recording(original);
  const std::ostringstream& text = recording.text;
  const GLubyte image[8] = {10, 20, 30, 41, 50, 60, 70, 80};
  original.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  EXPECT_EQ(original.gluBuild2DMipmaps(GL_TEXTURE_2D, GL_LUMINANCE8, 4, 2, GL_LUMINANCE, GL_UNSIGNED_BYTE, image), 0);
  ASSERT_NE(text.str().find("gluBuild2DMipmaps("), std::string::npos) << text.str();
  ReplayResult replay = replay_trace_text(text.str(), "glu.pass", ".");
  for (int level = 0; level < 3; ++level) {
    const int count = level == 0 ? 8 : level == 1 ? 2 : 1;
    EXPECT_EQ(level_bytes(*replay.context, GL_TEXTURE_2D, level, count), level_bytes(original, GL_TEXTURE_2D, level, count))
        << level;
  }
  EXPECT_EQ(level_bytes(*replay.context, GL_TEXTURE_2D, 1, 2), (std::vector<GLubyte>{35, 55}));
}

}  // namespace
