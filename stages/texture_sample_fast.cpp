// Texture sampling's fast paths (§3.8.5 for the common cases of the shadow-map programs):
// NEAREST and LINEAR with REPLACE over a whole span, on a LevelGeometry, each as a scalar loop
// and an AVX2 kernel that does the same IEEE operations in the same order. The general path
// they stand in for is sample_texture (texture_sample.cpp); TextureStage chooses
// (stages/kernel_paths.hpp), and the tests compare all three bit for bit.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "pipeline/fixed_point.hpp"
#include "stages/avx2.hpp"
#include "stages/kernel_paths.hpp"
#include "stages/texture_sample.hpp"
#include "stages/texture_wrap.hpp"

namespace passim {

namespace {

// The footprint of (s, t) on a LevelGeometry, as filter_level finds it: wrap, scale, the lower
// texel, the fractions; false when the coordinates are not finite or a texel lies beyond the
// stored ones (the border colour: the general path). 1D: t01 = t00, t11 = t10, beta = 0.
struct Footprint {
  const std::uint16_t *t00, *t10, *t01, *t11;  // the texels' codes
  double alpha, beta;
};
inline bool linear_footprint(const LevelGeometry& l, double s, double t, Footprint& f) {
  if (!std::isfinite(s) || !std::isfinite(t)) return false;
  const int b = l.border, w = l.w, h = l.h, dims = l.dims;
  const double uu = wrap_coordinate(s, l.wrap_s, l.edge_s) * w - 0.5;
  const double vv = dims == 2 ? wrap_coordinate(t, l.wrap_t, l.edge_t) * h - 0.5 : 0.0;
  const double fu = floor_exact(uu), fv = dims == 2 ? floor_exact(vv) : 0.0;
  const int i0 = static_cast<int>(fu), j0 = static_cast<int>(fv);
  f.alpha = uu - fu;
  f.beta = vv - fv;
  const int i[2] = {wrap_index(i0, l.wrap_s, w), wrap_index(i0 + 1, l.wrap_s, w)};
  const int j[2] = {dims == 2 ? wrap_index(j0, l.wrap_t, h) : 0, dims == 2 ? wrap_index(j0 + 1, l.wrap_t, h) : 0};
  if (i[0] < -b || i[1] >= w + b || i[1] < -b || i[0] >= w + b) return false;
  if (dims == 2 && (j[0] < -b || j[1] >= h + b || j[1] < -b || j[0] >= h + b)) return false;
  auto at = [&](int x, int y) {
    return l.texels + 4 * (static_cast<std::size_t>(y + l.row_border) * static_cast<std::size_t>(l.width) +
                           static_cast<std::size_t>(x + b));
  };
  f.t00 = at(i[0], j[0]);
  f.t10 = at(i[1], j[0]);
  f.t01 = dims == 2 ? at(i[0], j[1]) : f.t00;
  f.t11 = dims == 2 ? at(i[1], j[1]) : f.t10;
  return true;
}

void count_footprint(const LevelGeometry& l, Counters& counters) {
  const std::uint64_t texels = l.dims == 2 ? 4 : 2;
  counters.texels_fetched += texels;
  counters.texture_bits_read += texels * static_cast<std::uint64_t>(l.bits_per_texel);
}

// The scalar reference's span loop (the AVX2 kernel does the same four fragments at a time):
// each fragment's footprint, or general[i] = 1; `filter` writes the codes of one fragment
// from its footprint.
template <class Filter>
[[gnu::always_inline]] inline std::uint64_t for_each_footprint(const LevelGeometry& l, const FragmentSpan& span,
                                                               std::uint8_t* general, Counters& counters,
                                                               Filter&& filter) {
  std::uint64_t filtered = 0;
  for (int i = 0; i < span.count; ++i) {
    Footprint f;
    general[i] = !linear_footprint(l, span.s[i], span.t[i], f);
    if (general[i]) continue;
    ++filtered;
    count_footprint(l, counters);
    filter(f, span.rgba + 4 * i);
  }
  return filtered;
}

}  // namespace

std::uint64_t linear_replace_span_scalar(const LevelGeometry& l, const FragmentSpan& span,
                                         const std::array<int, 4>& bits, const std::array<bool, 4>& replace,
                                         std::uint8_t* general, Counters& counters) {
  const TexelDecoding& d = *l.decoding;
  return for_each_footprint(l, span, general, counters, [&](const Footprint& f, std::uint16_t* c) {
    for (int k = 0; k < 4; ++k) {
      // Component k's value of a texel: its table's entry for the code in slot source[k].
      const double* table = d.values.data() + (static_cast<std::size_t>(k) << d.code_bits);
      const auto v = [&](const std::uint16_t* texel) { return table[texel[d.source[static_cast<std::size_t>(k)]]]; };
      const double r = l.dims == 2 ? lerp_2d(f.alpha, f.beta, v(f.t00), v(f.t10), v(f.t01), v(f.t11))
                                   : lerp_1d(f.alpha, v(f.t00), v(f.t10));
      if (replace[static_cast<std::size_t>(k)]) c[k] = static_cast<std::uint16_t>(float_to_fixed(r, bits[static_cast<std::size_t>(k)]));
    }
  });
}

#if defined(PASSIM_HAVE_AVX2_KERNEL)
namespace {

// wrap_coordinate on four finite coordinates: REPEAT's s − floor(s) (ROUNDPD's floor is
// floor_exact's value), CLAMP's and CLAMP_TO_EDGE's std::clamp as MAXPD/MINPD (equal for
// finite values).
__attribute__((target("avx2"))) inline __m256d wrap_coordinate_4(__m256d s, GLenum mode, double edge) {
  if (mode == GL_REPEAT) return _mm256_sub_pd(s, _mm256_floor_pd(s));
  const double lo = mode == GL_CLAMP_TO_EDGE ? edge : 0.0;
  return _mm256_min_pd(_mm256_max_pd(s, _mm256_set1_pd(lo)), _mm256_set1_pd(1.0 - lo));
}

// wrap_index on four lower indices i0 and their i0 + 1. Under REPEAT the wrapped coordinate
// lies in [0, 1], so i0 = floor(u − 1/2) lies in [−1, size − 1] and one conditional add or
// subtract of `size` is i mod size; the clamping modes leave indices alone.
__attribute__((target("avx2"))) inline void wrap_index_4(__m128i i0, GLenum mode, int size, __m128i& lo,
                                                         __m128i& hi) {
  const __m128i i1 = _mm_add_epi32(i0, _mm_set1_epi32(1));
  if (mode != GL_REPEAT) {
    lo = i0;
    hi = i1;
    return;
  }
  const __m128i n = _mm_set1_epi32(size);
  lo = _mm_add_epi32(i0, _mm_and_si128(_mm_cmplt_epi32(i0, _mm_setzero_si128()), n));
  hi = _mm_sub_epi32(i1, _mm_andnot_si128(_mm_cmplt_epi32(i1, n), n));
}

// The bits of a fragment's four 16-bit codes (as one 64-bit word) that REPLACE leaves alone.
std::uint64_t kept_bits(const std::array<bool, 4>& replace) {
  std::uint64_t keep = 0;
  for (std::size_t k = 0; k < 4; ++k)
    if (!replace[k]) keep |= std::uint64_t{0xffff} << (16 * k);
  return keep;
}
// The fragment's codes `c` take `codes` where `keep` is clear.
inline void merge_codes(std::uint16_t* c, std::uint64_t codes, std::uint64_t keep) {
  std::uint64_t old = 0;
  std::memcpy(&old, c, sizeof old);
  const std::uint64_t now = (old & keep) | (codes & ~keep);
  std::memcpy(c, &now, sizeof now);
}

// Four coordinates from a span, the lanes past its end (n < 4) at 0.
__attribute__((target("avx2"))) inline __m256d load_4(const double* x, int n) {
  if (n == 4) return _mm256_loadu_pd(x);
  alignas(32) double padded[4] = {0, 0, 0, 0};
  std::copy(x, x + n, padded);
  return _mm256_load_pd(padded);
}

// A texel's four values (the decoding's source slots) by its division form
// (TexelDecoding::by_division): each code over its divisor, the constant components blended in.
// IEEE division, so the very values of the table, checked for every code when the decoding was
// made. (Not a gather from the table: slower than the division on CPUs with the gather-data-
// sampling mitigation.)
struct DivisionDecoding {
  __m256d divisor, constant, is_constant;
};
__attribute__((target("avx2"))) inline __m256d texel_values_by_division_4(const std::array<std::uint8_t, 4>& source,
                                                                          const DivisionDecoding& d,
                                                                          const std::uint16_t* t) {
  const __m128i codes = _mm_setr_epi32(t[source[0]], t[source[1]], t[source[2]], t[source[3]]);
  const __m256d quotient = _mm256_div_pd(_mm256_cvtepi32_pd(codes), d.divisor);
  return _mm256_blendv_pd(quotient, d.constant, d.is_constant);
}

// Lanes whose two indices both lie in [−border, size + border): linear_footprint's test.
__attribute__((target("avx2"))) inline __m128i stored_4(__m128i lo, __m128i hi, int border, int size) {
  const __m128i first = _mm_set1_epi32(-border - 1), end = _mm_set1_epi32(size + border);
  const __m128i lo_in = _mm_and_si128(_mm_cmpgt_epi32(lo, first), _mm_cmplt_epi32(lo, end));
  const __m128i hi_in = _mm_and_si128(_mm_cmpgt_epi32(hi, first), _mm_cmplt_epi32(hi, end));
  return _mm_and_si128(lo_in, hi_in);
}

}  // namespace

// linear_footprint and the filter on four fragments at a time: wrap, scale, floor, fractions,
// indices and weights in lanes (the same IEEE operations as the scalar reference, in the same
// order: no FMA under -ffp-contract=off and with mul/add intrinsics); then per fragment the
// four components at once — each weight times its texel, summed left to right — and
// float_to_fixed (clamp_nan_low to [0, 1], times 2^bits − 1, + 0.5, truncated). The codes
// `replace` selects are merged into the fragment's four with one mask.
__attribute__((target("avx2"))) std::uint64_t linear_replace_span_avx2(const LevelGeometry& l, const FragmentSpan& span,
                                                                       const std::array<int, 4>& bits,
                                                                       const std::array<bool, 4>& replace,
                                                                       std::uint8_t* general, Counters& counters) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
  const __m256d scale = _mm256_setr_pd(static_cast<double>(max_code(bits[0])), static_cast<double>(max_code(bits[1])),
                                       static_cast<double>(max_code(bits[2])), static_cast<double>(max_code(bits[3])));
  const std::uint64_t keep = kept_bits(replace);
  const bool two = l.dims == 2;
  const __m256d w_size = _mm256_set1_pd(static_cast<double>(l.w)), h_size = _mm256_set1_pd(static_cast<double>(l.h));
  const std::size_t row = static_cast<std::size_t>(l.width);
  const std::uint16_t* origin =
      l.texels + 4 * (static_cast<std::size_t>(l.row_border) * row + static_cast<std::size_t>(l.border));
  const TexelDecoding& d = *l.decoding;
  const DivisionDecoding division{
      _mm256_setr_pd(d.divisor[0], d.divisor[1], d.divisor[2], d.divisor[3]),
      _mm256_setr_pd(d.constant[0], d.constant[1], d.constant[2], d.constant[3]),
      _mm256_castsi256_pd(_mm256_setr_epi64x(d.is_constant[0] ? -1 : 0, d.is_constant[1] ? -1 : 0,
                                             d.is_constant[2] ? -1 : 0, d.is_constant[3] ? -1 : 0))};

  std::uint64_t filtered = 0;
  for (int i0 = 0; i0 < span.count; i0 += 4) {
    const int n = std::min(4, span.count - i0);
    __m256d s = load_4(span.s + i0, n), t = load_4(span.t + i0, n);
    // Finite lanes: x − x is 0 exactly for finite x, NaN for NaN and ±inf. The others take
    // 0 here (their results are discarded) so that no conversion sees a NaN.
    const __m256d finite = _mm256_and_pd(_mm256_cmp_pd(_mm256_sub_pd(s, s), zero, _CMP_EQ_OQ),
                                         _mm256_cmp_pd(_mm256_sub_pd(t, t), zero, _CMP_EQ_OQ));
    s = _mm256_and_pd(s, finite);
    t = _mm256_and_pd(t, finite);
    const __m256d uu = _mm256_sub_pd(_mm256_mul_pd(wrap_coordinate_4(s, l.wrap_s, l.edge_s), w_size), half);
    const __m256d fu = _mm256_floor_pd(uu);
    const __m256d alpha = _mm256_sub_pd(uu, fu);
    __m128i ilo, ihi;
    wrap_index_4(_mm256_cvttpd_epi32(fu), l.wrap_s, l.w, ilo, ihi);
    __m128i stored = stored_4(ilo, ihi, l.border, l.w);
    __m128i jlo = _mm_setzero_si128(), jhi = _mm_setzero_si128();
    __m256d beta = zero;
    if (two) {
      const __m256d vv = _mm256_sub_pd(_mm256_mul_pd(wrap_coordinate_4(t, l.wrap_t, l.edge_t), h_size), half);
      const __m256d fv = _mm256_floor_pd(vv);
      beta = _mm256_sub_pd(vv, fv);
      wrap_index_4(_mm256_cvttpd_epi32(fv), l.wrap_t, l.h, jlo, jhi);
      stored = _mm_and_si128(stored, stored_4(jlo, jhi, l.border, l.h));
    }
    const int lanes = _mm_movemask_ps(_mm_castsi128_ps(stored)) & _mm256_movemask_pd(finite) & ((1 << n) - 1);
    // The weights as lerp_1d / lerp_2d form them.
    const __m256d not_alpha = _mm256_sub_pd(one, alpha), not_beta = _mm256_sub_pd(one, beta);
    alignas(32) double w00[4], w10[4], w01[4], w11[4];
    if (two) {
      _mm256_store_pd(w00, _mm256_mul_pd(not_alpha, not_beta));
      _mm256_store_pd(w10, _mm256_mul_pd(alpha, not_beta));
      _mm256_store_pd(w01, _mm256_mul_pd(not_alpha, beta));
      _mm256_store_pd(w11, _mm256_mul_pd(alpha, beta));
    } else {
      _mm256_store_pd(w00, not_alpha);
      _mm256_store_pd(w10, alpha);
    }
    // Element offsets from `origin` of the four texels' codes, (j·row + i)·4, in 64 bits
    // (VPMULDQ: the signed 32-bit j times the row length).
    const __m256i row64 = _mm256_set1_epi64x(static_cast<long long>(row));
    const __m256i j0 = _mm256_mul_epi32(_mm256_cvtepi32_epi64(jlo), row64);
    const __m256i j1 = _mm256_mul_epi32(_mm256_cvtepi32_epi64(jhi), row64);
    const __m256i il = _mm256_cvtepi32_epi64(ilo), ih = _mm256_cvtepi32_epi64(ihi);
    alignas(32) std::int64_t o00[4], o10[4], o01[4], o11[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(o00), _mm256_slli_epi64(_mm256_add_epi64(j0, il), 2));
    _mm256_store_si256(reinterpret_cast<__m256i*>(o10), _mm256_slli_epi64(_mm256_add_epi64(j0, ih), 2));
    _mm256_store_si256(reinterpret_cast<__m256i*>(o01), _mm256_slli_epi64(_mm256_add_epi64(j1, il), 2));
    _mm256_store_si256(reinterpret_cast<__m256i*>(o11), _mm256_slli_epi64(_mm256_add_epi64(j1, ih), 2));
    for (int k = 0; k < n; ++k) {
      const bool ok = (lanes >> k) & 1;
      general[i0 + k] = !ok;
      if (!ok) continue;
      const __m256d v00 = texel_values_by_division_4(d.source, division, origin + o00[k]);
      const __m256d v10 = texel_values_by_division_4(d.source, division, origin + o10[k]);
      __m256d r;
      if (two) {
        r = _mm256_mul_pd(_mm256_broadcast_sd(w00 + k), v00);
        r = _mm256_add_pd(r, _mm256_mul_pd(_mm256_broadcast_sd(w10 + k), v10));
        const __m256d v01 = texel_values_by_division_4(d.source, division, origin + o01[k]);
        const __m256d v11 = texel_values_by_division_4(d.source, division, origin + o11[k]);
        r = _mm256_add_pd(r, _mm256_mul_pd(_mm256_broadcast_sd(w01 + k), v01));
        r = _mm256_add_pd(r, _mm256_mul_pd(_mm256_broadcast_sd(w11 + k), v11));
      } else {
        r = _mm256_add_pd(_mm256_mul_pd(_mm256_broadcast_sd(w00 + k), v00),
                          _mm256_mul_pd(_mm256_broadcast_sd(w10 + k), v10));
      }
      const __m256d x = _mm256_add_pd(_mm256_mul_pd(clamp_nan_low_4(r, zero, one), scale), half);
      // Codes are at most 65535: PACKUSDW keeps them exactly.
      const __m128i codes = _mm_packus_epi32(_mm256_cvttpd_epi32(x), _mm_setzero_si128());
      merge_codes(span.rgba + 4 * (i0 + k), static_cast<std::uint64_t>(_mm_cvtsi128_si64(codes)), keep);
    }
    filtered += static_cast<std::uint64_t>(__builtin_popcount(static_cast<unsigned>(lanes)));
  }
  const std::uint64_t texels = two ? 4 : 2;
  counters.texels_fetched += filtered * texels;
  counters.texture_bits_read += filtered * texels * static_cast<std::uint64_t>(l.bits_per_texel);
  return filtered;
}
#endif

std::uint64_t linear_replace_span(const LevelGeometry& l, const FragmentSpan& span, const std::array<int, 4>& bits,
                                  const std::array<bool, 4>& replace, std::uint8_t* general, Counters& counters) {
#if defined(PASSIM_HAVE_AVX2_KERNEL)
  if (use_avx2() && l.decoding->by_division) return linear_replace_span_avx2(l, span, bits, replace, general, counters);
#endif
  return linear_replace_span_scalar(l, span, bits, replace, general, counters);
}

void nearest_replace_span_scalar(const LevelGeometry& l, const std::uint16_t* codes, const FragmentSpan& span,
                                 const std::array<bool, 4>& replace) {
  const TexelDecoding& d = *l.decoding;
  for (int n = 0; n < span.count; ++n) {
    const double s = std::isfinite(span.s[n]) ? span.s[n] : 0.0;  // as sample_texture
    const double t = std::isfinite(span.t[n]) ? span.t[n] : 0.0;
    // Every wrap mode puts the coordinate in [0, 1], so nearest_index lies in [0, size − 1]:
    // a stored texel, never the border or the border colour.
    const int i = nearest_index(s, l.wrap_s, l.edge_s, l.w);
    const int j = l.dims == 2 ? nearest_index(t, l.wrap_t, l.edge_t, l.h) : 0;
    const std::uint16_t* texel =
        l.texels + 4 * (static_cast<std::size_t>(j + l.row_border) * static_cast<std::size_t>(l.width) +
                        static_cast<std::size_t>(i + l.border));
    std::uint16_t* c = span.rgba + 4 * n;
    for (std::size_t k = 0; k < 4; ++k)
      if (replace[k]) c[k] = codes[(k << d.code_bits) | texel[d.source[k]]];
  }
}

#if defined(PASSIM_HAVE_AVX2_KERNEL)
// NEAREST on four fragments at a time: the wrapped coordinate lies in [0, 1] under every wrap
// mode, so floor(u) clamped to size − 1 is a stored texel's index (wrap_index leaves it alone).
__attribute__((target("avx2"))) void nearest_replace_span_avx2(const LevelGeometry& l, const std::uint16_t* codes,
                                                               const FragmentSpan& span,
                                                               const std::array<bool, 4>& replace) {
  const std::uint64_t keep = kept_bits(replace);
  const bool two = l.dims == 2;
  const __m256d zero = _mm256_setzero_pd();
  const __m256d w_size = _mm256_set1_pd(static_cast<double>(l.w)), h_size = _mm256_set1_pd(static_cast<double>(l.h));
  const __m128i w_last = _mm_set1_epi32(l.w - 1), h_last = _mm_set1_epi32(l.h - 1);
  const __m256i row64 = _mm256_set1_epi64x(static_cast<long long>(l.width));
  const std::uint16_t* origin =
      l.texels + 4 * (static_cast<std::size_t>(l.row_border) * static_cast<std::size_t>(l.width) +
                      static_cast<std::size_t>(l.border));
  const TexelDecoding& d = *l.decoding;
  const std::size_t bits = static_cast<std::size_t>(d.code_bits);
  for (int i0 = 0; i0 < span.count; i0 += 4) {
    const int n = std::min(4, span.count - i0);
    __m256d s = load_4(span.s + i0, n), t = load_4(span.t + i0, n);
    // Non-finite coordinates sample at 0 (x − x is NaN exactly for NaN and ±inf).
    s = _mm256_and_pd(s, _mm256_cmp_pd(_mm256_sub_pd(s, s), zero, _CMP_EQ_OQ));
    t = _mm256_and_pd(t, _mm256_cmp_pd(_mm256_sub_pd(t, t), zero, _CMP_EQ_OQ));
    const __m128i i = _mm_min_epi32(
        _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_mul_pd(wrap_coordinate_4(s, l.wrap_s, l.edge_s), w_size))), w_last);
    __m128i j = _mm_setzero_si128();
    if (two)
      j = _mm_min_epi32(
          _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_mul_pd(wrap_coordinate_4(t, l.wrap_t, l.edge_t), h_size))),
          h_last);
    // Element offsets (j·width + i)·4 of the texels' codes, in 64 bits.
    alignas(32) std::int64_t offset[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(offset),
                       _mm256_slli_epi64(_mm256_add_epi64(_mm256_mul_epi32(_mm256_cvtepi32_epi64(j), row64),
                                                          _mm256_cvtepi32_epi64(i)),
                                         2));
    for (int k = 0; k < n; ++k) {
      // The texel's REPLACE codes, one table entry per component, as one 64-bit word.
      const std::uint16_t* t = origin + offset[k];
      const std::uint64_t texel = std::uint64_t{codes[t[d.source[0]]]} |
                                  std::uint64_t{codes[(1u << bits) | t[d.source[1]]]} << 16 |
                                  std::uint64_t{codes[(2u << bits) | t[d.source[2]]]} << 32 |
                                  std::uint64_t{codes[(3u << bits) | t[d.source[3]]]} << 48;
      merge_codes(span.rgba + 4 * (i0 + k), texel, keep);
    }
  }
}
#endif

void nearest_replace_span(const LevelGeometry& l, const std::uint16_t* codes, const FragmentSpan& span,
                          const std::array<bool, 4>& replace) {
#if defined(PASSIM_HAVE_AVX2_KERNEL)
  if (use_avx2()) return nearest_replace_span_avx2(l, codes, span, replace);
#endif
  nearest_replace_span_scalar(l, codes, span, replace);
}

}  // namespace passim
