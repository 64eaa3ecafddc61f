// Precision studies: the provenance of a loss, and the sweep's order.
#include <gtest/gtest.h>

#include <cmath>

#include "programs/study.hpp"

namespace passim {
namespace {

TEST(Provenance, A12BitMapCopiedIntoAn8BitTextureIsWhereInformationIsLost) {
  // The example: a 12-bit shadow map copied into an 8-bit texture format loses its
  // low bits. Widening the texture formats alone recovers precision; widening the
  // colour table (floats, A24) or the accumulation buffer changes nothing.
  ProgramOptions o;
  o.program = "fast-pcf";
  o.filter = 2;
  o.scene = "paper";
  o.width = 200;
  o.height = 150;
  o.color_bits = 12;
  o.texture_bits = 8;
  const std::vector<ProvenanceRow> rows = precision_provenance(o);
  ASSERT_EQ(rows.size(), 5u);
  const double base = rows[0].error.precision_bits;
  EXPECT_EQ(rows[2].stage, "texture formats widened to 16 bits");
  EXPECT_GT(rows[2].error.precision_bits, base + 0.5) << "widening the textures should recover bits";
  EXPECT_NEAR(rows[3].error.precision_bits, base, 1e-12) << "the colour table holds floats (A24)";
  EXPECT_NEAR(rows[4].error.precision_bits, base, 1e-12) << "fast-pcf 2x2 does not accumulate";
}

TEST(StudySweep, PointsVaryBitsFastestAndKeepTheBiasAsADepth) {
  StudySweep s;
  s.base.program = "pcf";
  s.color_bits = {8, 12};
  s.biases = {0.5, 1.0};
  const std::vector<ProgramOptions> p = s.points();
  ASSERT_EQ(p.size(), 4u);
  EXPECT_EQ(p[0].color_bits, 8);
  EXPECT_EQ(p[1].color_bits, 12);
  // Half an 8-bit step of depth: 0.5 steps at 8 bits, 0.5·16 = 8 steps at 12.
  EXPECT_DOUBLE_EQ(p[0].bias, 0.5);
  EXPECT_DOUBLE_EQ(p[1].bias, 8.0);
  EXPECT_DOUBLE_EQ(p[3].bias, 16.0);
  StudySweep other = s;
  other.biases = {0.5, 2.0};
  EXPECT_NE(s.id(), other.id());
}

}  // namespace
}  // namespace passim
