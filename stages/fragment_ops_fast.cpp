// The per-fragment operations' fast paths (§4.1, for the states the multipass programs use
// most), each standing in for the general path of fragment_ops.cpp with the same planes and
// counters: blending with unit factors in integers (scalar, SSE2), blending in reals over a
// span (AVX2, beside the scalar loop), and the depth test with a colour replace in one pass.
// FragmentOps::plan chooses (stages/kernel_paths.hpp); tests/fragment_ops_test.cpp compares.
#include <algorithm>
#include <cstring>
#include <type_traits>

#include "pipeline/fixed_point.hpp"
#include "stages/avx2.hpp"
#include "stages/fragment_ops.hpp"
#include "stages/kernel_paths.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace passim {

std::uint32_t blend_codes_unit_factors(GLenum equation, bool src_one, bool dst_one, std::uint32_t s,
                                       std::uint32_t d, std::uint32_t max) {
  const std::uint32_t sp = src_one ? s : 0, dp = dst_one ? d : 0;
  switch (equation) {
    case GL_FUNC_SUBTRACT: return sp > dp ? sp - dp : 0;
    case GL_FUNC_REVERSE_SUBTRACT: return dp > sp ? dp - sp : 0;
    case GL_MIN: return std::min(s, d);
    case GL_MAX: return std::max(s, d);
    default: return std::min(sp + dp, max);  // GL_FUNC_ADD
  }
}

bool blend_has_unit_factors(GLenum equation, GLenum src_factor, GLenum dst_factor) {
  auto unit = [](GLenum f) { return f == GL_ZERO || f == GL_ONE; };
  return equation == GL_MIN || equation == GL_MAX || (unit(src_factor) && unit(dst_factor));
}

std::uint64_t blend_span_unit_factors_scalar(const UnitFactorBlend& b, const std::uint8_t* live,
                                             const std::uint16_t* src, std::uint16_t* dst, int begin, int end) {
  std::uint64_t blended = 0;
  // One loop per equation, so that the equation's case is chosen once per span.
  auto blend_loop = [&](auto equation) {
    for (int i = begin; i < end; ++i) {
      if (!live[i]) continue;
      ++blended;
      std::uint16_t* d = dst + 4 * i;
      const std::uint16_t* s = src + 4 * i;
      for (int k = 0; k < 4; ++k)
        if (b.written[k])
          d[k] = static_cast<std::uint16_t>(
              blend_codes_unit_factors(decltype(equation)::value, b.src_one, b.dst_one, s[k], d[k], b.max[k]));
    }
  };
  switch (b.equation) {
    case GL_FUNC_SUBTRACT: blend_loop(std::integral_constant<GLenum, GL_FUNC_SUBTRACT>{}); break;
    case GL_FUNC_REVERSE_SUBTRACT: blend_loop(std::integral_constant<GLenum, GL_FUNC_REVERSE_SUBTRACT>{}); break;
    case GL_MIN: blend_loop(std::integral_constant<GLenum, GL_MIN>{}); break;
    case GL_MAX: blend_loop(std::integral_constant<GLenum, GL_MAX>{}); break;
    default: blend_loop(std::integral_constant<GLenum, GL_FUNC_ADD>{}); break;
  }
  return blended;
}

#if defined(__SSE2__)
namespace {
// Two fragments (8 codes, all below 2^16) per step: a − sat(a − b) = min(a, b), b + sat(a − b)
// = max(a, b), sat(a + b) is a + b or at least 65535 >= max, so min(sat(a + b), max) is
// blend_codes_unit_factors's min(a + b, max).
template <GLenum Equation>
std::uint64_t blend_pairs_sse2(const UnitFactorBlend& b, const std::uint8_t* live, const std::uint16_t* src,
                               std::uint16_t* dst, int begin, int end) {
  auto lanes64 = [](std::uint64_t lo, std::uint64_t hi) {
    return _mm_set_epi64x(static_cast<long long>(hi), static_cast<long long>(lo));
  };
  std::uint64_t written = 0, max = 0;
  for (int k = 0; k < 4; ++k) {
    if (b.written[k]) written |= std::uint64_t{0xffff} << (16 * k);
    max |= static_cast<std::uint64_t>(b.max[k] & 0xffff) << (16 * k);
  }
  const __m128i max2 = lanes64(max, max);
  const __m128i src_keep = b.src_one ? _mm_set1_epi32(-1) : _mm_setzero_si128();
  const __m128i dst_keep = b.dst_one ? _mm_set1_epi32(-1) : _mm_setzero_si128();
  std::uint64_t blended = 0;
  int i = begin;
  for (; i + 2 <= end; i += 2) {
    if (!live[i] && !live[i + 1]) continue;
    const std::uint64_t m0 = live[i] ? written : 0, m1 = live[i + 1] ? written : 0;
    blended += static_cast<std::uint64_t>(live[i] != 0) + static_cast<std::uint64_t>(live[i + 1] != 0);
    const __m128i s = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + 4 * i));
    const __m128i d = _mm_loadu_si128(reinterpret_cast<const __m128i*>(dst + 4 * i));
    const __m128i sp = _mm_and_si128(s, src_keep), dp = _mm_and_si128(d, dst_keep);
    __m128i r;
    if constexpr (Equation == GL_FUNC_SUBTRACT) {
      r = _mm_subs_epu16(sp, dp);
    } else if constexpr (Equation == GL_FUNC_REVERSE_SUBTRACT) {
      r = _mm_subs_epu16(dp, sp);
    } else if constexpr (Equation == GL_MIN) {
      r = _mm_sub_epi16(s, _mm_subs_epu16(s, d));
    } else if constexpr (Equation == GL_MAX) {
      r = _mm_add_epi16(d, _mm_subs_epu16(s, d));
    } else {
      const __m128i sum = _mm_adds_epu16(sp, dp);
      r = _mm_sub_epi16(sum, _mm_subs_epu16(sum, max2));
    }
    const __m128i m = lanes64(m0, m1);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(dst + 4 * i), _mm_or_si128(_mm_and_si128(r, m), _mm_andnot_si128(m, d)));
  }
  return blended + blend_span_unit_factors_scalar(b, live, src, dst, i, end);
}
}  // namespace
#endif

std::uint64_t blend_span_unit_factors(const UnitFactorBlend& b, const std::uint8_t* live, const std::uint16_t* src,
                                      std::uint16_t* dst, int begin, int end) {
#if defined(__SSE2__)
  if (use_sse2()) {
    switch (b.equation) {
      case GL_FUNC_SUBTRACT: return blend_pairs_sse2<GL_FUNC_SUBTRACT>(b, live, src, dst, begin, end);
      case GL_FUNC_REVERSE_SUBTRACT: return blend_pairs_sse2<GL_FUNC_REVERSE_SUBTRACT>(b, live, src, dst, begin, end);
      case GL_MIN: return blend_pairs_sse2<GL_MIN>(b, live, src, dst, begin, end);
      case GL_MAX: return blend_pairs_sse2<GL_MAX>(b, live, src, dst, begin, end);
      default: return blend_pairs_sse2<GL_FUNC_ADD>(b, live, src, dst, begin, end);
    }
  }
#endif
  return blend_span_unit_factors_scalar(b, live, src, dst, begin, end);
}


#if defined(PASSIM_HAVE_AVX2_KERNEL)
namespace {
using V4 = __m256d;

// (Helpers, not lambdas: a lambda does not take its enclosing function's target.)
__attribute__((target("avx2"))) inline V4 alpha(V4 v) { return _mm256_permute4x64_pd(v, 0xff); }

// blend_factor for the four components at once; lane k is blend_factor(f, k, ...).
__attribute__((target("avx2"))) inline V4 blend_factor_4(GLenum f, V4 s, V4 d, V4 c, V4 one) {
  switch (f) {
    case GL_ZERO: return _mm256_setzero_pd();
    case GL_ONE: return one;
    case GL_SRC_COLOR: return s;
    case GL_ONE_MINUS_SRC_COLOR: return _mm256_sub_pd(one, s);
    case GL_DST_COLOR: return d;
    case GL_ONE_MINUS_DST_COLOR: return _mm256_sub_pd(one, d);
    case GL_SRC_ALPHA: return alpha(s);
    case GL_ONE_MINUS_SRC_ALPHA: return _mm256_sub_pd(one, alpha(s));
    case GL_DST_ALPHA: return alpha(d);
    case GL_ONE_MINUS_DST_ALPHA: return _mm256_sub_pd(one, alpha(d));
    case GL_CONSTANT_COLOR: return c;
    case GL_ONE_MINUS_CONSTANT_COLOR: return _mm256_sub_pd(one, c);
    case GL_CONSTANT_ALPHA: return alpha(c);
    case GL_ONE_MINUS_CONSTANT_ALPHA: return _mm256_sub_pd(one, alpha(c));
    case GL_SRC_ALPHA_SATURATE: {
      // std::min(As, 1 − Ad) for RGB, 1 for A. Both operands are >= +0 and not NaN (codes
      // over their maximum), where MINPD and std::min agree.
      const V4 m = _mm256_min_pd(alpha(s), _mm256_sub_pd(one, alpha(d)));
      return _mm256_blend_pd(m, one, 0x8);
    }
    default: return _mm256_setzero_pd();
  }
}

// quantise(c, bits) lane by lane (float_to_fixed then back): clamp, ·m, +0.5, truncate, /m.
__attribute__((target("avx2"))) inline V4 quantise_4(V4 c, V4 m) {
  const V4 t = _mm256_add_pd(_mm256_mul_pd(clamp_nan_low_4(c, _mm256_setzero_pd(), _mm256_set1_pd(1.0)), m),
                             _mm256_set1_pd(0.5));
  return _mm256_div_pd(_mm256_round_pd(t, _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC), m);
}

// Four codes as reals: k / m lane by lane, 1 where `none` has its sign bit set.
__attribute__((target("avx2"))) inline V4 code_reals_4(const std::uint16_t* codes, V4 m, V4 none) {
  const __m128i k32 = _mm_cvtepu16_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(codes)));
  return _mm256_blendv_pd(_mm256_div_pd(_mm256_cvtepi32_pd(k32), m), _mm256_set1_pd(1.0), none);
}

__attribute__((target("avx2"))) inline V4 product_4(V4 x, V4 f, bool rounded, V4 m) {
  const V4 p = _mm256_mul_pd(x, f);
  return rounded ? quantise_4(p, m) : p;
}

template <GLenum Equation>
__attribute__((target("avx2"))) std::uint64_t blend_reals_avx2(const RealBlend& b, const std::uint8_t* live,
                                                               const std::uint16_t* src, std::uint16_t* dst, int begin,
                                                               int end) {
  // Per lane: the maxima (1 where a channel has no bits, whose value is then replaced by 1).
  double src_max[4], dst_max[4], src_none[4], dst_none[4];
  std::uint64_t written = 0;
  for (int k = 0; k < 4; ++k) {
    src_max[k] = b.src_bits[k] ? static_cast<double>(max_code(b.src_bits[k])) : 1.0;
    dst_max[k] = b.dst_bits[k] ? static_cast<double>(max_code(b.dst_bits[k])) : 1.0;
    src_none[k] = b.src_bits[k] ? 0.0 : -1.0;  // sign bit set: blendv takes 1
    dst_none[k] = b.dst_bits[k] ? 0.0 : -1.0;
    if (b.written[k]) written |= std::uint64_t{0xffff} << (16 * k);
  }
  const V4 one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd(), half = _mm256_set1_pd(0.5);
  const V4 sm = _mm256_loadu_pd(src_max), dm = _mm256_loadu_pd(dst_max);
  const V4 s_none = _mm256_loadu_pd(src_none), d_none = _mm256_loadu_pd(dst_none);
  const V4 c = _mm256_loadu_pd(b.constant);
  std::uint64_t blended = 0;
  for (int i = begin; i < end; ++i) {
    if (!live[i]) continue;
    ++blended;
    std::uint16_t* d = dst + 4 * i;
    const V4 sv = code_reals_4(src + 4 * i, sm, s_none), dv = code_reals_4(d, dm, d_none);
    V4 r;
    if constexpr (Equation == GL_MIN) {
      r = _mm256_min_pd(sv, dv);  // values >= +0, never NaN: MINPD is std::min
    } else if constexpr (Equation == GL_MAX) {
      r = _mm256_max_pd(sv, dv);
    } else {
      const V4 ps = product_4(sv, blend_factor_4(b.src_factor, sv, dv, c, one), b.products_rounded, dm);
      const V4 pd = product_4(dv, blend_factor_4(b.dst_factor, sv, dv, c, one), b.products_rounded, dm);
      if constexpr (Equation == GL_FUNC_SUBTRACT) r = _mm256_sub_pd(ps, pd);
      else if constexpr (Equation == GL_FUNC_REVERSE_SUBTRACT) r = _mm256_sub_pd(pd, ps);
      else r = _mm256_add_pd(ps, pd);
    }
    // float_to_fixed: clamp (NaN to 0), ·m + 0.5, truncated (the sum is >= 0.5 and < 2^16).
    const V4 t = _mm256_add_pd(_mm256_mul_pd(clamp_nan_low_4(r, zero, one), dm), half);
    const __m128i codes32 = _mm256_cvttpd_epi32(t);
    std::uint64_t out, old;
    _mm_storel_epi64(reinterpret_cast<__m128i*>(&out), _mm_packus_epi32(codes32, codes32));
    std::memcpy(&old, d, sizeof old);
    old = (old & ~written) | (out & written);
    std::memcpy(d, &old, sizeof old);
  }
  return blended;
}
}  // namespace
#endif

std::uint64_t blend_span_reals(const RealBlend& b, const std::uint8_t* live, const std::uint16_t* src,
                               std::uint16_t* dst, int begin, int end) {
#if defined(PASSIM_HAVE_AVX2_KERNEL)
  if (use_avx2()) {
    switch (b.equation) {
      case GL_FUNC_SUBTRACT: return blend_reals_avx2<GL_FUNC_SUBTRACT>(b, live, src, dst, begin, end);
      case GL_FUNC_REVERSE_SUBTRACT: return blend_reals_avx2<GL_FUNC_REVERSE_SUBTRACT>(b, live, src, dst, begin, end);
      case GL_MIN: return blend_reals_avx2<GL_MIN>(b, live, src, dst, begin, end);
      case GL_MAX: return blend_reals_avx2<GL_MAX>(b, live, src, dst, begin, end);
      default: return blend_reals_avx2<GL_FUNC_ADD>(b, live, src, dst, begin, end);
    }
  }
#endif
  return blend_span_reals_scalar(b, live, src, dst, begin, end);
}


namespace {

// Depth test (optional) and colour replace in one pass: the common case of the general
// path below, giving the same planes and counters (tests/fragment_ops_test.cpp compares them).
template <class Cmp, bool kDepth, bool kAllChannels>
std::uint64_t replace_loop(Cmp cmp, bool depth_write, const std::array<bool, 4>& mask, const FragmentSpan& span,
                           int begin, int end, std::uint32_t* depth, std::uint16_t* color) {
  std::uint64_t passed = 0;
  for (int i = begin; i < end; ++i) {
    if constexpr (kDepth) {
      const std::uint32_t z = span.depth[i];
      if (!cmp(z, depth[i])) continue;
      if (depth_write) depth[i] = z;
    }
    ++passed;
    const std::uint16_t* src = span.rgba + 4 * i;
    std::uint16_t* d = color + 4 * i;
    if constexpr (kAllChannels) {
      std::memcpy(d, src, 4 * sizeof(std::uint16_t));
    } else {
      for (int k = 0; k < 4; ++k)
        if (mask[k]) d[k] = src[k];
    }
  }
  return passed;
}

template <bool kDepth, bool kAll, class Cmp>
std::uint64_t replace_dispatch(Cmp cmp, bool w, const std::array<bool, 4>& m, const FragmentSpan& s, int b, int e,
                               std::uint32_t* depth, std::uint16_t* color) {
  return replace_loop<Cmp, kDepth, kAll>(cmp, w, m, s, b, e, depth, color);
}

template <bool kAll>
std::uint64_t replace_by_func(bool depth_on, GLenum func, bool w, const std::array<bool, 4>& m, const FragmentSpan& s,
                              int b, int e, std::uint32_t* depth, std::uint16_t* color) {
  using U = std::uint32_t;
  if (!depth_on) return replace_dispatch<false, kAll>([](U, U) { return true; }, w, m, s, b, e, depth, color);
  switch (func) {
    case GL_NEVER: return replace_dispatch<true, kAll>([](U, U) { return false; }, w, m, s, b, e, depth, color);
    case GL_LESS: return replace_dispatch<true, kAll>([](U a, U c) { return a < c; }, w, m, s, b, e, depth, color);
    case GL_EQUAL: return replace_dispatch<true, kAll>([](U a, U c) { return a == c; }, w, m, s, b, e, depth, color);
    case GL_LEQUAL: return replace_dispatch<true, kAll>([](U a, U c) { return a <= c; }, w, m, s, b, e, depth, color);
    case GL_GREATER: return replace_dispatch<true, kAll>([](U a, U c) { return a > c; }, w, m, s, b, e, depth, color);
    case GL_NOTEQUAL: return replace_dispatch<true, kAll>([](U a, U c) { return a != c; }, w, m, s, b, e, depth, color);
    case GL_GEQUAL: return replace_dispatch<true, kAll>([](U a, U c) { return a >= c; }, w, m, s, b, e, depth, color);
    default: return replace_dispatch<true, kAll>([](U, U) { return true; }, w, m, s, b, e, depth, color);
  }
}

}  // namespace


void FragmentOps::replace_span(const FragmentSpan& span, int begin, int end, Counters& counters) {
  const FragmentOpsState& ops = *in_.ops;
  const FramebufferControlState& ctl = *in_.control;
  const FramebufferConfig& cfg = fb_.config;
  const std::size_t row_base = fb_.pixel_index(span.x0, span.y);
  const bool depth_on = ops.depth_test && cfg.depth_bits > 0;
  std::uint32_t* depth = depth_on ? fb_.depth.data() + row_base : nullptr;
  std::uint16_t* color = fb_.color[static_cast<int>(in_.draw_buffers->front())].rgba.data() + 4 * row_base;
  const auto& m = ctl.color_mask;
  const bool all = m[0] && m[1] && m[2] && m[3];
  const std::uint64_t passed =
      all ? replace_by_func<true>(depth_on, ops.depth_func, ctl.depth_mask, m, span, begin, end, depth, color)
          : replace_by_func<false>(depth_on, ops.depth_func, ctl.depth_mask, m, span, begin, end, depth, color);
  const std::uint64_t n = static_cast<std::uint64_t>(end - begin);
  if (depth_on) {
    const std::uint64_t bits = static_cast<std::uint64_t>(cfg.depth_bits);
    counters.depth_bits_read += n * bits;
    if (ctl.depth_mask) counters.depth_bits_written += passed * bits;
    counters.killed_depth += n - passed;
  }
  counters.fragments_written += passed;
  int mask_bits = 0;
  for (int k = 0; k < 4; ++k)
    if (m[k]) mask_bits += cfg.color_bits[k];
  counters.color_bits_written += passed * static_cast<std::uint64_t>(mask_bits);
}

}  // namespace passim
