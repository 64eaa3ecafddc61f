// The LINEAR/REPLACE span kernel: AVX2 against its scalar reference, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <random>

#include "pipeline/fixed_point.hpp"
#include "stages/avx2.hpp"
#include "stages/texture_sample.hpp"

namespace passim {
namespace {

// Wrap modes, odd coordinates (REPEAT at the extremes: s − floor(s) rounds to 1 for a tiny
// negative s; huge coordinates are whole numbers, floor_exact's std::floor branch).
const GLenum kWraps[] = {GL_REPEAT, GL_CLAMP, GL_CLAMP_TO_EDGE};
const double kOdd[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity(), -0.0, 1.0, 0.0, 0.5, -1e-17, 1e20, -4.5e15,
                       0x1.fffffffffffffp-1, 2147483648.5};

// A random 1D or 2D level of up to 16 texels a side, with or without a border, and random wraps.
LevelGeometry random_level(std::mt19937& rng) {
  LevelGeometry l;
  l.dims = 1 + static_cast<int>(rng() % 2);
  l.border = static_cast<int>(rng() % 2);
  l.w = 1 << (rng() % 5);
  l.h = l.dims == 2 ? 1 << (rng() % 5) : 1;
  l.width = l.w + 2 * l.border;
  l.row_border = l.dims == 2 ? l.border : 0;
  l.edge_s = 1.0 / (2.0 * l.w);
  l.edge_t = 1.0 / (2.0 * l.h);
  l.bits_per_texel = 32;
  l.wrap_s = kWraps[rng() % 3];
  l.wrap_t = kWraps[rng() % 3];
  return l;
}
std::size_t texel_count(const LevelGeometry& l) {
  return static_cast<std::size_t>(l.width) * static_cast<std::size_t>(l.dims == 2 ? l.h + 2 * l.border : 1);
}

// Two identical spans of n fragments with random coordinates (some odd) and colours.
void random_spans(std::mt19937& rng, int n, FragmentSpan& a, FragmentSpan& b) {
  std::uniform_real_distribution<double> coord(-1.5, 2.5);
  for (int i = 0; i < n; ++i) {
    a.s[i] = b.s[i] = rng() % 30 == 0 ? kOdd[rng() % std::size(kOdd)] : coord(rng);
    a.t[i] = b.t[i] = rng() % 30 == 0 ? kOdd[rng() % std::size(kOdd)] : coord(rng);
    for (int k = 0; k < 4; ++k) a.rgba[4 * i + k] = b.rgba[4 * i + k] = static_cast<std::uint16_t>(rng());
  }
}

// The two spans agree fragment for fragment: live flags and codes.
void expect_same_spans(int round, int n, const FragmentSpan& a, const FragmentSpan& b) {
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(a.live[i], b.live[i]) << round << " " << i;
    for (int k = 0; k < 4; ++k) ASSERT_EQ(a.rgba[4 * i + k], b.rgba[4 * i + k]) << round << " " << i << " " << k;
  }
}

TEST(TextureKernels, LinearReplaceAvx2EqualsScalar) {
  if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this processor: only the scalar reference runs";
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> texel(-0.2, 1.2);
  int compared = 0;
  for (int round = 0; round < 1000; ++round) {
    LevelGeometry l = random_level(rng);
    std::vector<double> values(4 * texel_count(l));
    for (double& v : values) v = rng() % 50 == 0 ? kOdd[rng() % std::size(kOdd)] : texel(rng);
    l.values = values.data();
    const int n = 1 + static_cast<int>(rng() % 40);
    SpanBuffers a(n), b(n);
    FragmentSpan sa = a.span(0, 0, n), sb = b.span(0, 0, n);
    random_spans(rng, n, sa, sb);
    const std::array<int, 4> bits{static_cast<int>(1 + rng() % 16), static_cast<int>(1 + rng() % 16),
                                  static_cast<int>(1 + rng() % 16), static_cast<int>(1 + rng() % 16)};
    const std::array<bool, 4> replace{rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0};
    Counters ca, cb;
    const std::uint64_t fa = linear_replace_span(l, sa, bits, replace, sa.live, ca);
    const std::uint64_t fb = linear_replace_span_scalar(l, sb, bits, replace, sb.live, cb);
    ASSERT_EQ(fa, fb) << round;
    ASSERT_TRUE(ca == cb) << round;
    expect_same_spans(round, n, sa, sb);
    compared += static_cast<int>(fa);
  }
  EXPECT_GT(compared, 3000);
}

TEST(TextureKernels, NearestReplaceAvx2EqualsScalar) {
  if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this processor: only the scalar reference runs";
  std::mt19937 rng(23);
  int compared = 0;
  for (int round = 0; round < 1000; ++round) {
    const LevelGeometry l = random_level(rng);
    std::vector<std::uint16_t> codes(4 * texel_count(l));
    for (auto& c : codes) c = static_cast<std::uint16_t>(rng());
    const int n = 1 + static_cast<int>(rng() % 40);
    SpanBuffers a(n), b(n);
    FragmentSpan sa = a.span(0, 0, n), sb = b.span(0, 0, n);
    random_spans(rng, n, sa, sb);
    const std::array<bool, 4> replace{rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0, rng() % 4 != 0};
    nearest_replace_span(l, codes.data(), sa, replace);
    nearest_replace_span_scalar(l, codes.data(), sb, replace);
    expect_same_spans(round, n, sa, sb);
    compared += n;
  }
  EXPECT_GT(compared, 10000);
}

TEST(TextureKernels, ReplaceCodesByTableEqualTheDecodedTexels) {
  // codes_at tabulates per code when a level has more texels than codes: for every base
  // format, against float_to_fixed of the decoded reals (values()), at fragment widths
  // narrower, equal and wider than the texel's.
  std::mt19937 rng(29);
  const GLint formats[] = {GL_ALPHA8, GL_LUMINANCE8, GL_LUMINANCE12_ALPHA4, GL_INTENSITY12, GL_RGB5, GL_RGBA8,
                           GL_RGB10_A2, GL_RGBA16, GL_LUMINANCE4, GL_R3_G3_B2};
  for (GLint internal : formats) {
    for (const std::array<int, 4>& bits : {std::array<int, 4>{8, 8, 8, 8}, std::array<int, 4>{12, 12, 12, 12},
                                           std::array<int, 4>{5, 6, 5, 1}, std::array<int, 4>{16, 16, 16, 16}}) {
      TextureLevel level;
      level.width = 256;
      level.height = 260;  // 66,560 texels: more than the codes of a 16-bit component
      level.format = *internal_format(internal);
      const InternalFormat& f = level.format;
      const int width[4] = {std::max({f.red, f.luminance, f.intensity}), f.green, f.blue, f.alpha};
      level.texels.resize(4u * 256u * 260u);
      for (std::size_t p = 0; p < level.texels.size(); ++p) {
        const int w = width[p % 4];
        level.texels[p] = w == 0 ? 0u : static_cast<std::uint32_t>(rng() % (1u << w));
      }
      const std::vector<double>& values = level.values();
      const auto& codes = level.codes_at(bits);
      ASSERT_EQ(values.size(), codes.size());
      for (std::size_t p = 0; p < codes.size(); ++p)
        ASSERT_EQ(float_to_fixed(values[p], bits[p % 4]), codes[p]) << internal << " element " << p;
      // Made by ranges of rows (as the raster lanes make them: here 7 rows at a time, last
      // range first), the same codes; and likewise for a level of fewer texels than codes,
      // converted texel by texel.
      const std::vector<std::uint16_t> whole(codes.begin(), codes.end());
      const RowSplitter backwards = [](int rows, const std::function<void(int, int)>& body) {
        for (int first = (rows - 1) / 7 * 7; first >= 0; first -= 7) body(first, std::min(rows, first + 7));
      };
      // (The cache's storage is reused unset: poison it, so that codes left from before show.)
      const auto poison = [&level] {
        level.replace_codes.assign(level.replace_codes.capacity(), 0xBEEF);
        level.texels_changed();
      };
      poison();
      const auto& split = level.codes_at(bits, &backwards);
      ASSERT_TRUE(std::equal(whole.begin(), whole.end(), split.begin(), split.end())) << internal;
      level.height = 20;  // 5,120 texels
      level.texels.resize(4u * 256u * 20u);
      level.texels_changed();
      const std::vector<std::uint16_t> small_whole(level.codes_at(bits).begin(), level.codes_at(bits).end());
      poison();
      const auto& small_split = level.codes_at(bits, &backwards);
      ASSERT_TRUE(std::equal(small_whole.begin(), small_whole.end(), small_split.begin(), small_split.end()))
          << internal;
    }
  }
}

}  // namespace
}  // namespace passim
