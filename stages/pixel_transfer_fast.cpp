// The pixel-transfer stages' AVX2 row kernels (§3.6.5: scale and bias, the colour tables, the
// colour matrix, the final conversion to codes), four components at a time in the same IEEE
// operations and order as the scalar loops of pixel_transfer.cpp, which are the reference;
// pixel_transfer.cpp chooses (stages/kernel_paths.hpp) and tests/pixel_transfer_kernels_test.cpp
// compares them bit for bit.
#include <algorithm>
#include <bit>
#include <cmath>

#include "pipeline/fixed_point.hpp"
#include "stages/avx2.hpp"
#include "stages/pixel_transfer.hpp"

namespace passim {

// ---------------------------------------------------------------- AVX2 row kernels

#if defined(PASSIM_HAVE_AVX2_KERNEL)
namespace {

// A colour table as the kernel reads it: component k is looked up at its own index and
// takes the entry's component `from[k]` where `replace` has it (Table 3.13, as the switch
// in color_table_lookup spells out case by case).
struct TableLookup {
  const Rgba* entries = nullptr;
  double w1 = 0.0;
  bool replace[4] = {};
  int from[4] = {0, 0, 0, 0};
};

TableLookup table_lookup(const ColorTable* t) {
  TableLookup l;
  if (!t) return l;
  l.entries = t->entries.data();
  l.w1 = static_cast<double>(t->entries.size() - 1);
  const bool alpha = t->base == GL_ALPHA || t->base == GL_LUMINANCE_ALPHA || t->base == GL_INTENSITY ||
                     t->base == GL_RGBA;
  const bool colour = t->base != GL_ALPHA;
  const bool single = t->base == GL_LUMINANCE || t->base == GL_LUMINANCE_ALPHA || t->base == GL_INTENSITY;
  for (int k = 0; k < 3; ++k) {
    l.replace[k] = colour;
    l.from[k] = single ? 0 : k;
  }
  l.replace[3] = alpha;
  l.from[3] = t->base == GL_INTENSITY ? 0 : 3;
  return l;
}

__attribute__((target("avx2"))) inline __m256d load_rgba(const Rgba& p) { return _mm256_loadu_pd(p.data()); }
__attribute__((target("avx2"))) inline __m256d to_vec(const Vec4& v) { return _mm256_setr_pd(v[0], v[1], v[2], v[3]); }

__attribute__((target("avx2"))) inline __m256d clamp_unit(__m256d c) {
  return clamp_nan_low_4(c, _mm256_setzero_pd(), _mm256_set1_pd(1.0));
}

__attribute__((target("avx2"))) inline __m256d lookup(const TableLookup& t, __m256d c, __m256d mask) {
  // The index ⌊clamp(c)·(W − 1) + ½⌋ of every component (the argument is >= 0.5: truncation
  // is the floor); all four lie in [0, W − 1], so every load is inside the table.
  alignas(16) std::int32_t index[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(index),
                  _mm256_cvttpd_epi32(_mm256_add_pd(_mm256_mul_pd(clamp_unit(c), _mm256_set1_pd(t.w1)), _mm256_set1_pd(0.5))));
  const __m256d looked_up = _mm256_setr_pd(t.entries[index[0]][static_cast<std::size_t>(t.from[0])],
                                           t.entries[index[1]][static_cast<std::size_t>(t.from[1])],
                                           t.entries[index[2]][static_cast<std::size_t>(t.from[2])],
                                           t.entries[index[3]][static_cast<std::size_t>(t.from[3])]);
  return _mm256_blendv_pd(c, looked_up, mask);
}

__attribute__((target("avx2"))) inline __m256d replace_mask(const TableLookup& t) {
  return _mm256_castsi256_pd(_mm256_setr_epi64x(t.replace[0] ? -1 : 0, t.replace[1] ? -1 : 0, t.replace[2] ? -1 : 0,
                                                t.replace[3] ? -1 : 0));
}

}  // namespace

__attribute__((target("avx2"))) void transfer_pre_convolution_avx2(const TransferPlan& plan, Rgba* pixels,
                                                                   std::size_t n) {
  const PixelTransferState& s = *plan.state;
  const __m256d scale = to_vec(s.scale), bias = to_vec(s.bias);
  const TableLookup table = table_lookup(plan.tables[kColorTable]);
  const __m256d mask = replace_mask(table);
  for (std::size_t i = 0; i < n; ++i) {
    __m256d c = load_rgba(pixels[i]);
    if (plan.scale_bias) c = _mm256_add_pd(_mm256_mul_pd(c, scale), bias);
    if (table.entries) c = lookup(table, c, mask);
    _mm256_storeu_pd(pixels[i].data(), c);
  }
}

__attribute__((target("avx2"))) void transfer_post_convolution_avx2(const TransferPlan& plan, Rgba* pixels,
                                                                    std::size_t n) {
  const PixelTransferState& s = *plan.state;
  const TableLookup post_convolution = table_lookup(plan.tables[kPostConvolutionTable]);
  const TableLookup post_matrix = table_lookup(plan.tables[kPostColorMatrixTable]);
  const __m256d mask1 = replace_mask(post_convolution), mask2 = replace_mask(post_matrix);
  const Mat4& m = *plan.matrix;
  const __m256d col0 = to_vec(m[0]), col1 = to_vec(m[1]), col2 = to_vec(m[2]), col3 = to_vec(m[3]);
  const __m256d scale = to_vec(s.post_color_matrix_scale), bias = to_vec(s.post_color_matrix_bias);
  for (std::size_t i = 0; i < n; ++i) {
    __m256d c = load_rgba(pixels[i]);
    if (post_convolution.entries) c = lookup(post_convolution, c, mask1);
    if (plan.color_matrix) {
      // M·c as GLM evaluates it: (m0·c0 + m1·c1) + (m2·c2 + m3·c3), column by column.
      const __m256d sum01 = _mm256_add_pd(_mm256_mul_pd(col0, _mm256_permute4x64_pd(c, 0x00)),
                                          _mm256_mul_pd(col1, _mm256_permute4x64_pd(c, 0x55)));
      const __m256d sum23 = _mm256_add_pd(_mm256_mul_pd(col2, _mm256_permute4x64_pd(c, 0xAA)),
                                          _mm256_mul_pd(col3, _mm256_permute4x64_pd(c, 0xFF)));
      c = _mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(sum01, sum23), scale), bias);
    }
    if (post_matrix.entries) c = lookup(post_matrix, c, mask2);
    _mm256_storeu_pd(pixels[i].data(), c);
  }
}

__attribute__((target("avx2"))) void color_codes_from_reals_avx2(const Rgba* pixels, std::size_t n, const double max[4],
                                                                 std::uint16_t* out) {
  const __m256d scale = _mm256_loadu_pd(max), half = _mm256_set1_pd(0.5);
  for (std::size_t i = 0; i < n; ++i) {
    const __m128i codes = _mm256_cvttpd_epi32(_mm256_add_pd(_mm256_mul_pd(clamp_unit(load_rgba(pixels[i])), scale), half));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 4 * i), _mm_packus_epi32(codes, codes));  // codes < 2^16
  }
}

#else
void transfer_pre_convolution_avx2(const TransferPlan& plan, Rgba* pixels, std::size_t n) {
  transfer_pre_convolution_scalar(plan, pixels, n);
}
void transfer_post_convolution_avx2(const TransferPlan& plan, Rgba* pixels, std::size_t n) {
  transfer_post_convolution_scalar(plan, pixels, n);
}
void color_codes_from_reals_avx2(const Rgba* pixels, std::size_t n, const double max[4], std::uint16_t* out) {
  color_codes_from_reals_scalar(pixels, n, max, out);
}
#endif

}  // namespace passim
