// §2.13.9 conversions and the tie rule A1, with values computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/fixed_point.hpp"

using namespace passim;

TEST(FixedPoint, MaxCode) {
  EXPECT_EQ(max_code(1), 1u);
  EXPECT_EQ(max_code(8), 255u);
  EXPECT_EQ(max_code(12), 4095u);
  EXPECT_EQ(max_code(16), 65535u);
  EXPECT_EQ(max_code(24), 16777215u);
  EXPECT_EQ(max_code(32), 4294967295u);
}

TEST(FixedPoint, RoundToNearestTiesUp) {
  // 0.5 · 255 = 127.5 -> 128; 0.5 · 4095 = 2047.5 -> 2048 (A1: ties go up).
  EXPECT_EQ(float_to_fixed(0.5, 8), 128u);
  EXPECT_EQ(float_to_fixed(0.5, 12), 2048u);
  // The product is taken in double, then the tie rule applies to it: double(0.1)·255,
  // double(0.3)·4095 and double(0.7)·255 all round to exact ties (25.5, 1228.5, 178.5).
  EXPECT_EQ(float_to_fixed(0.1, 8), 26u);
  EXPECT_EQ(float_to_fixed(0.3, 12), 1229u);
  EXPECT_EQ(float_to_fixed(0.7, 8), 179u);
  EXPECT_EQ(float_to_fixed(1.0 / 3.0, 8), 85u);     // 85.0
  EXPECT_EQ(float_to_fixed(1.0 / 3.0, 12), 1365u);  // 1365.0
}

TEST(FixedPoint, ClampsAndNaN) {
  EXPECT_EQ(float_to_fixed(-0.25, 8), 0u);
  EXPECT_EQ(float_to_fixed(1.75, 8), 255u);
  EXPECT_EQ(float_to_fixed(1.75, 12), 4095u);
  EXPECT_EQ(float_to_fixed(std::nan(""), 8), 0u);
  EXPECT_EQ(float_to_fixed(INFINITY, 12), 4095u);
  EXPECT_EQ(float_to_fixed(-INFINITY, 12), 0u);
}

TEST(FixedPoint, FixedToFloatEndpointsExact) {
  EXPECT_EQ(fixed_to_float(0, 8), 0.0);
  EXPECT_EQ(fixed_to_float(255, 8), 1.0);
  EXPECT_EQ(fixed_to_float(4095, 12), 1.0);
  EXPECT_DOUBLE_EQ(fixed_to_float(128, 8), 128.0 / 255.0);
  EXPECT_EQ(fixed_to_float(0, 0), 1.0);  // a channel with no bits reads as 1 (absent alpha)
}

TEST(FixedPoint, RoundTripEveryCode) {
  for (int bits : {1, 4, 8, 12, 16})
    for (std::uint32_t k = 0; k <= max_code(bits); ++k) ASSERT_EQ(float_to_fixed(fixed_to_float(k, bits), bits), k);
}

TEST(FixedPoint, EightToTwelveBitsA2) {
  // A2: round(u · 4095/255): u = 9 -> 144.53 -> 145 (0x091), not bit replication (0x090).
  EXPECT_EQ(rescale_code(9, 8, 12), 0x091u);
  EXPECT_EQ(rescale_code(255, 8, 12), 4095u);
  EXPECT_EQ(rescale_code(128, 8, 12), 2056u);  // 128·4095/255 = 2055.53 -> 2056
  // 12 -> 8: 2048·255/4095 = 127.53 -> 128
  EXPECT_EQ(rescale_code(2048, 12, 8), 128u);
}

TEST(FixedPoint, FloorExactMatchesStdFloor) {
  const double values[] = {0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2.999999999, -2.000000001, 1e15 + 0.5, -1e15 - 0.5,
                           4.5e15, -4.5e15, 1e300, -1e300, INFINITY, -INFINITY, 0.49999999999999994};
  for (double v : values) EXPECT_EQ(floor_exact(v), std::floor(v)) << v;
  EXPECT_TRUE(std::isnan(floor_exact(std::nan(""))));
  for (std::uint32_t k = 0; k <= 4095; ++k) ASSERT_EQ(code_value(k, 12), fixed_to_float(k, 12));
}
