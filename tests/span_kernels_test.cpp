// The SIMD span kernels agree bit for bit with their scalar references.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "stages/span_kernels.hpp"

using namespace passim;

TEST(SpanKernels, DepthCodesMatchTheScalarReference) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 1.2), slope(-0.01, 0.01);
  for (int bits : {16, 24, 30, 32}) {
    const double scale = static_cast<double>((std::uint64_t{1} << bits) - 1);
    for (int trial = 0; trial < 300; ++trial) {
      const int n = 1 + static_cast<int>(rng() % 67), x0 = static_cast<int>(rng() % 4000);
      SpanPlane z{u(rng), slope(rng)};
      if (trial % 50 == 0) z.row = std::numeric_limits<double>::quiet_NaN();
      if (trial % 50 == 1) z.row = -0.0;
      if (trial % 50 == 2) z.d_dx = std::numeric_limits<double>::infinity();
      const double offset = trial % 3 ? 0.0 : slope(rng);
      std::vector<std::uint32_t> a(n), b(n);
      depth_codes_scalar(z, offset, x0, 17.3125, n, scale, a.data());
      depth_codes(z, offset, x0, 17.3125, n, scale, b.data());
      ASSERT_EQ(a, b) << "bits " << bits << " trial " << trial;
      if (depth_codes_has_avx2()) {
        std::vector<std::uint32_t> w(n);
        depth_codes_wide(z, offset, x0, 17.3125, n, scale, w.data());
        ASSERT_EQ(a, w) << "AVX2, bits " << bits << " trial " << trial;
      }
      std::vector<std::uint32_t> p(static_cast<std::size_t>(n + kSpanPadding));
      depth_codes_padded(z, offset, x0, 17.3125, n, scale, p.data());
      p.resize(static_cast<std::size_t>(n));
      ASSERT_EQ(a, p) << "padded, bits " << bits << " trial " << trial;
    }
  }
}

TEST(SpanKernels, ColorCodesMatchTheScalarReference) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.3, 1.3), slope(-0.05, 0.05), q(0.05, 2.0);
  for (int bits : {1, 8, 12, 16}) {
    const double s = static_cast<double>((1u << bits) - 1);
    const double scale[4] = {s, s, s, s};
    for (int trial = 0; trial < 300; ++trial) {
      const int n = 1 + static_cast<int>(rng() % 67), x0 = static_cast<int>(rng() % 4000);
      const SpanPlane qp{q(rng), slope(rng) * 0.01};
      SpanPlane c[4];
      for (auto& p : c) p = SpanPlane{u(rng) * qp.row, slope(rng)};
      if (trial % 40 == 0) c[1].row = std::numeric_limits<double>::quiet_NaN();
      std::vector<std::uint16_t> a(4 * n), b(4 * n);
      color_codes_scalar(qp, c, scale, x0, 3.0625, n, a.data());
      color_codes(qp, c, scale, x0, 3.0625, n, b.data());
      ASSERT_EQ(a, b) << "bits " << bits << " trial " << trial;
      if (color_codes_has_avx2()) {
        std::vector<std::uint16_t> w(4 * n);
        color_codes_wide(qp, c, scale, x0, 3.0625, n, w.data());
        ASSERT_EQ(a, w) << "AVX2, bits " << bits << " trial " << trial;
      }
      std::vector<std::uint16_t> p(static_cast<std::size_t>(4 * (n + kSpanPadding)));
      color_codes_padded(qp, c, scale, x0, 3.0625, n, p.data());
      p.resize(static_cast<std::size_t>(4 * n));
      ASSERT_EQ(a, p) << "padded, bits " << bits << " trial " << trial;
    }
  }
}

TEST(SpanKernels, TextureCoordinatesMatchTheScalarReference) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-3.0, 3.0), slope(-0.05, 0.05), q(-0.5, 2.0);
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 67), x0 = static_cast<int>(rng() % 4000);
    SpanPlane stq[4];
    for (int k = 0; k < 3; ++k) stq[k] = SpanPlane{u(rng), slope(rng)};
    stq[3] = SpanPlane{q(rng), slope(rng) * 0.01};
    if (trial % 40 == 0) stq[3] = SpanPlane{0.0, 0.0};  // q = 0: ±inf and NaN coordinates
    if (trial % 40 == 1) stq[1].row = std::numeric_limits<double>::quiet_NaN();
    // All three, or only s (a 1D texture) or s and t (2D): the others are 0.
    const int used = 1 + trial % 3;
    std::vector<double> s0(n), t0(n), r0(n), s1(n, 7.0), t1(n, 7.0), r1(n, 7.0);
    texture_coordinates_scalar(stq, x0, 5.5625, n, 3, s0.data(), t0.data(), r0.data());
    texture_coordinates(stq, x0, 5.5625, n, used, s1.data(), t1.data(), r1.data());
    if (used < 3) std::fill(r0.begin(), r0.end(), 0.0);
    if (used < 2) std::fill(t0.begin(), t0.end(), 0.0);
    // Bit for bit (NaN payloads included): memcmp, not ==.
    ASSERT_EQ(0, std::memcmp(s0.data(), s1.data(), sizeof(double) * n)) << trial;
    ASSERT_EQ(0, std::memcmp(t0.data(), t1.data(), sizeof(double) * n)) << trial;
    ASSERT_EQ(0, std::memcmp(r0.data(), r1.data(), sizeof(double) * n)) << trial;
    compared += n;
    // One fragment checked against the formula written out (eq. 3.4 as a ratio of planes).
    const double dx = (static_cast<double>(x0) + 0.5) - 5.5625;
    const double expect = (stq[0].row + stq[0].d_dx * dx) / (stq[3].row + stq[3].d_dx * dx);
    if (!std::isnan(expect)) {
      ASSERT_EQ(expect, s1[0]) << trial;
    }
  }
  EXPECT_GT(compared, 50000);
}
