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

// Formats of every base, with widths from 1 to 16 bits.
const GLint kFormats[] = {GL_ALPHA8, GL_LUMINANCE8, GL_LUMINANCE12_ALPHA4, GL_INTENSITY12, GL_RGB5, GL_RGBA8,
                          GL_RGB10_A2, GL_RGBA16, GL_LUMINANCE4, GL_R3_G3_B2, GL_LUMINANCE16_ALPHA16, GL_RGBA2};

// A level of `texels` random codes of a format (each below 2^its width), as TextureLevel
// stores them.
TextureLevel random_texels(std::mt19937& rng, GLint internal, std::size_t texels) {
  TextureLevel level;
  level.format = *internal_format(internal);
  const InternalFormat& f = level.format;
  const int width[4] = {std::max({f.red, f.luminance, f.intensity}), f.green, f.blue, f.alpha};
  level.texels.resize(4 * texels);
  for (std::size_t p = 0; p < level.texels.size(); ++p) {
    const int w = width[p % 4];
    level.texels[p] = w == 0 ? 0u : static_cast<std::uint16_t>(rng() % (1u << w));
  }
  return level;
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
  int compared = 0;
  for (int round = 0; round < 1000; ++round) {
    LevelGeometry l = random_level(rng);
    const TextureLevel level = random_texels(rng, kFormats[rng() % std::size(kFormats)], texel_count(l));
    l.texels = level.texels.data();
    l.decoding = texel_decoding(level.format);
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
    LevelGeometry l = random_level(rng);
    const TextureLevel level = random_texels(rng, kFormats[rng() % std::size(kFormats)], texel_count(l));
    l.texels = level.texels.data();
    l.decoding = texel_decoding(level.format);
    const std::array<int, 4> bits{static_cast<int>(1 + rng() % 16), static_cast<int>(1 + rng() % 16),
                                  static_cast<int>(1 + rng() % 16), static_cast<int>(1 + rng() % 16)};
    const std::vector<std::uint16_t>& codes = l.decoding->replace_codes(bits);
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

TEST(TextureKernels, DecodingTablesEqualTheSpecsDivision) {
  // The fast paths read a texel's values and REPLACE codes from per-format tables
  // (TexelDecoding); the general sampler decodes each texel by §2.13.9's k / (2^b − 1)
  // (TextureLevel::decode). For every base format and random texels: the table's value of
  // each component is the division's, and its REPLACE code is float_to_fixed of it, at
  // fragment widths narrower, equal and wider than the texel's.
  std::mt19937 rng(29);
  for (GLint internal : kFormats) {
    const TextureLevel level = random_texels(rng, internal, 5000);
    const TexelDecoding* d = texel_decoding(level.format);
    ASSERT_NE(d, nullptr) << internal;
    EXPECT_TRUE(d->by_division) << internal;
    for (const std::array<int, 4>& bits : {std::array<int, 4>{8, 8, 8, 8}, std::array<int, 4>{12, 12, 12, 12},
                                           std::array<int, 4>{5, 6, 5, 1}, std::array<int, 4>{16, 16, 16, 16}}) {
      const std::vector<std::uint16_t>& replace = d->replace_codes(bits);
      for (std::size_t p = 0; p < 5000; ++p) {
        double want[4];
        level.decode(p, want);
        for (std::size_t k = 0; k < 4; ++k) {
          const std::size_t entry = (k << d->code_bits) | level.texels[4 * p + d->source[k]];
          ASSERT_EQ(d->values[entry], want[k]) << internal << " texel " << p << " component " << k;
          ASSERT_EQ(replace[entry], float_to_fixed(want[k], bits[k])) << internal << " texel " << p << " component " << k;
          // The division form the AVX2 LINEAR kernel computes (it is used for every format:
          // below), against the general sampler's decoding.
          const double code = static_cast<double>(level.texels[4 * p + d->source[k]]);
          ASSERT_EQ(d->is_constant[k] ? d->constant[k] : code / d->divisor[k], want[k])
              << internal << " texel " << p << " component " << k;
        }
      }
    }
  }
  // A depth code wider than 16 bits has no table (the general sampler alone reads it) and is
  // stored in two halves.
  TextureLevel depth;
  depth.format = *internal_format(GL_DEPTH_COMPONENT24);
  EXPECT_EQ(texel_decoding(depth.format), nullptr);
  depth.texels.resize(4);
  const std::uint32_t code[4] = {0xABCDEFu, 0, 0, 0};
  depth.set_texel(0, code);
  double v[4];
  depth.decode(0, v);
  EXPECT_EQ(v[0], static_cast<double>(0xABCDEF) / 16777215.0);
}

}  // namespace
}  // namespace passim
