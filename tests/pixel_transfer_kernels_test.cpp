// The pixel-transfer row kernels: the AVX2 kernels against the scalar reference, bit for bit,
// on random pixels (out of range, NaN, infinities and −0 included), random tables of every
// base format and size, random colour matrices and scales.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "pipeline/gl.hpp"
#include "pipeline/profile.hpp"
#include "stages/avx2.hpp"
#include "stages/pixel_transfer.hpp"

using namespace passim;

namespace {

bool same_bits(const std::vector<Rgba>& a, const std::vector<Rgba>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Rgba)) == 0;
}

std::vector<Rgba> random_pixels(std::mt19937& rng, std::size_t n) {
  std::uniform_real_distribution<double> value(-0.5, 1.5);
  const double special[] = {std::nan(""), INFINITY, -INFINITY, -0.0, 0.0, 1.0, 0.5, 1e-320};
  std::vector<Rgba> pixels(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 4; ++k) pixels[i][k] = rng() % 16 == 0 ? special[rng() % 8] : value(rng);
  return pixels;
}

void random_table(std::mt19937& rng, ColorTable& table) {
  const GLenum bases[] = {GL_ALPHA, GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_INTENSITY, GL_RGB, GL_RGBA};
  const std::size_t sizes[] = {1, 2, 16, 256, 4096};
  std::uniform_real_distribution<double> entry(0.0, 1.0);
  table.enabled = rng() % 4 != 0;
  table.base = bases[rng() % 6];
  table.entries.resize(sizes[rng() % 5]);
  for (Rgba& e : table.entries)
    for (double& v : e) v = entry(rng);
}

}  // namespace

TEST(PixelTransferKernels, Avx2MatchesTheScalarReferenceBitForBit) {
  if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this processor";
  std::mt19937 rng(1122);
  std::uniform_real_distribution<double> coefficient(-2.0, 2.0);
  for (int trial = 0; trial < 300; ++trial) {
    PixelTransferState state;
    if (rng() % 2)
      for (int k = 0; k < 4; ++k) {
        state.scale[k] = coefficient(rng);
        state.bias[k] = coefficient(rng);
      }
    for (ColorTable& t : state.tables) random_table(rng, t);
    Mat4 matrix(1.0);
    if (rng() % 3 != 0) {
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) matrix[c][r] = coefficient(rng);
      for (int k = 0; k < 4; ++k) {
        state.post_color_matrix_scale[k] = coefficient(rng);
        state.post_color_matrix_bias[k] = coefficient(rng);
      }
    }
    const TransferPlan plan = plan_transfer(state, matrix);
    const std::vector<Rgba> input = random_pixels(rng, 97);
    std::vector<Rgba> scalar = input, wide = input;
    transfer_pre_convolution_scalar(plan, scalar.data(), scalar.size());
    transfer_pre_convolution_avx2(plan, wide.data(), wide.size());
    ASSERT_TRUE(same_bits(scalar, wide)) << "pre-convolution, trial " << trial << ", table base "
                                         << enum_name(state.tables[0].base);
    transfer_post_convolution_scalar(plan, scalar.data(), scalar.size());
    transfer_post_convolution_avx2(plan, wide.data(), wide.size());
    ASSERT_TRUE(same_bits(scalar, wide)) << "post-convolution, trial " << trial;
    // The final conversion, at the widths 1, 5, 8, 12 and 16 in turn.
    const double max[4] = {1.0, 31.0, 4095.0, static_cast<double>(trial % 2 ? 65535 : 255)};
    std::vector<std::uint16_t> codes_scalar(4 * input.size()), codes_wide(4 * input.size());
    color_codes_from_reals_scalar(input.data(), input.size(), max, codes_scalar.data());
    color_codes_from_reals_avx2(input.data(), input.size(), max, codes_wide.data());
    ASSERT_EQ(codes_scalar, codes_wide) << "codes, trial " << trial;
  }
}

TEST(PixelTransferKernels, TheFinalConversionRoundsAsTheSpecSays) {
  // By hand at 8 bits: 0.5·255 = 127.5 -> 128 (tie up), 0.2·255 = 51 -> 51 (51.000000000000007),
  // 1.5 clamps to 255, −0.25 and NaN to 0.
  const Rgba pixels[2] = {{0.5, 0.2, 1.5, -0.25}, {std::nan(""), 1.0, 0.0, 0.998}};
  const double max[4] = {255, 255, 255, 255};
  std::uint16_t codes[8];
  color_codes_from_reals(pixels, 2, max, codes);
  const std::uint16_t expected[8] = {128, 51, 255, 0, 0, 255, 0, 254};  // 0.998·255 = 254.49 -> 254
  for (int i = 0; i < 8; ++i) EXPECT_EQ(codes[i], expected[i]) << i;
}

TEST(PixelTransferKernels, ConvolutionAvx2MatchesTheScalarReferenceBitForBit) {
  // Every filter size up to the largest any machine profile allows (1-11 x 1-11 for `ideal`),
  // general and separable, every base format and border mode, on images wider, narrower and
  // smaller than the filter.
  if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this processor";
  int largest_width = 0, largest_height = 0;
  for (const MachineProfile& p : machine_profiles()) {
    largest_width = std::max(largest_width, p.limits.max_convolution_width);
    largest_height = std::max(largest_height, p.limits.max_convolution_height);
  }
  ASSERT_GE(largest_width, 11);
  std::mt19937 rng(2211);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  const GLenum bases[] = {GL_ALPHA, GL_LUMINANCE, GL_LUMINANCE_ALPHA, GL_INTENSITY, GL_RGB, GL_RGBA};
  const GLenum borders[] = {GL_REDUCE, GL_CONSTANT_BORDER, GL_REPLICATE_BORDER};
  const int trials = 3 * largest_width * largest_height;
  for (int trial = 0; trial < trials; ++trial) {
    ConvolutionFilter f;
    f.base = bases[rng() % 6];
    f.border_mode = borders[rng() % 3];
    f.border_color = {coefficient(rng), coefficient(rng), coefficient(rng), coefficient(rng)};
    f.width = 1 + (trial / 3) % largest_width;  // every size, three times
    f.height = 1 + (trial / 3) / largest_width;
    f.separable = rng() % 4 == 0;
    auto random_rgba = [&] { return Rgba{coefficient(rng), coefficient(rng), coefficient(rng), coefficient(rng)}; };
    if (f.separable) {
      for (int n = 0; n < f.width; ++n) f.row.push_back(random_rgba());
      for (int m = 0; m < f.height; ++m) f.column.push_back(random_rgba());
    } else {
      for (int t = 0; t < f.width * f.height; ++t) f.taps.push_back(random_rgba());
    }
    const int width = 1 + static_cast<int>(rng() % 27), height = 1 + static_cast<int>(rng() % 15);
    const std::vector<Rgba> input = random_pixels(rng, static_cast<std::size_t>(width * height));
    std::vector<Rgba> scalar = input, wide = input;
    int ws = width, hs = height, ww = width, hw = height;
    Counters cs, cw;
    convolve(scalar, ws, hs, f, cs, ConvolutionKernel::Scalar);
    convolve(wide, ww, hw, f, cw, ConvolutionKernel::Fastest);
    ASSERT_EQ(ws, ww);
    ASSERT_EQ(hs, hw);
    ASSERT_TRUE(same_bits(scalar, wide)) << "trial " << trial << ": " << f.width << "x" << f.height << " on " << width
                                         << "x" << height << ", " << enum_name(f.base) << ", " << enum_name(f.border_mode);
    EXPECT_EQ(cs.convolution_taps, cw.convolution_taps);
  }
}
