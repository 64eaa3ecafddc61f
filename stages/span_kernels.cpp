#include "stages/span_kernels.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace passim {
namespace {

inline double centre_offset(int x, double x_ref) { return (static_cast<double>(x) + 0.5) - x_ref; }

// clamp to [0, 1] with NaN -> 0, then round half up (the argument is >= 0.5: truncation is floor).
inline std::uint32_t code(double v, double scale) {
  v = v > 0.0 ? v : 0.0;
  v = v < 1.0 ? v : 1.0;
  return static_cast<std::uint32_t>(v * scale + 0.5);
}

}  // namespace

void depth_codes_scalar(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                        std::uint32_t* out) {
  for (int i = 0; i < n; ++i) out[i] = code((z.row + z.d_dx * centre_offset(x0 + i, x_ref)) + offset, scale);
}

void color_codes_scalar(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                        std::uint16_t* out) {
  for (int i = 0; i < n; ++i) {
    const double dx = centre_offset(x0 + i, x_ref);
    const double inv_q = 1.0 / (q.row + q.d_dx * dx);
    for (int k = 0; k < 4; ++k)
      out[4 * i + k] = static_cast<std::uint16_t>(code((c[k].row + c[k].d_dx * dx) * inv_q, scale[k]));
  }
}

#if defined(__SSE2__)
namespace {

struct Lanes {
  __m128d zero = _mm_setzero_pd(), one = _mm_set1_pd(1.0), half = _mm_set1_pd(0.5);
  // MAXPD returns its second operand when the first is NaN: NaN -> 0, as the scalar rule.
  __m128d clamp(__m128d v) const { return _mm_min_pd(_mm_max_pd(v, zero), one); }
  __m128i codes(__m128d v, __m128d scale) const {
    return _mm_cvttpd_epi32(_mm_add_pd(_mm_mul_pd(clamp(v), scale), half));
  }
};

inline __m128d centre_offsets(int x, double x_ref) {
  const __m128d xs = _mm_cvtepi32_pd(_mm_set_epi32(0, 0, x + 1, x));
  return _mm_sub_pd(_mm_add_pd(xs, _mm_set1_pd(0.5)), _mm_set1_pd(x_ref));
}

}  // namespace

void depth_codes(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale, std::uint32_t* out) {
  if (scale >= 2147483647.0) return depth_codes_scalar(z, offset, x0, x_ref, n, scale, out);  // 31-32 bits
  const Lanes L;
  const __m128d row = _mm_set1_pd(z.row), d = _mm_set1_pd(z.d_dx), off = _mm_set1_pd(offset), s = _mm_set1_pd(scale);
  int i = 0;
  for (; i + 2 <= n; i += 2) {
    const __m128d dx = centre_offsets(x0 + i, x_ref);
    const __m128d v = _mm_add_pd(_mm_add_pd(row, _mm_mul_pd(d, dx)), off);
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + i), L.codes(v, s));
  }
  depth_codes_scalar(z, offset, x0 + i, x_ref, n - i, scale, out + i);
}

void color_codes(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                 std::uint16_t* out) {
  const Lanes L;
  const __m128d q_row = _mm_set1_pd(q.row), q_d = _mm_set1_pd(q.d_dx), one = _mm_set1_pd(1.0);
  __m128d c_row[4], c_d[4], s[4];
  for (int k = 0; k < 4; ++k) {
    c_row[k] = _mm_set1_pd(c[k].row);
    c_d[k] = _mm_set1_pd(c[k].d_dx);
    s[k] = _mm_set1_pd(scale[k]);
  }
  const __m128i bias = _mm_set1_epi32(32768), flip = _mm_set1_epi16(static_cast<short>(0x8000));
  int i = 0;
  for (; i + 2 <= n; i += 2) {
    const __m128d dx = centre_offsets(x0 + i, x_ref);
    const __m128d inv_q = _mm_div_pd(one, _mm_add_pd(q_row, _mm_mul_pd(q_d, dx)));
    __m128i k4[4];
    for (int k = 0; k < 4; ++k)
      k4[k] = L.codes(_mm_mul_pd(_mm_add_pd(c_row[k], _mm_mul_pd(c_d[k], dx)), inv_q), s[k]);
    // [r0 r1] [g0 g1] [b0 b1] [a0 a1] -> r0 g0 b0 a0 r1 g1 b1 a1 as unsigned 16-bit (values < 2^16:
    // biased into the signed range so that the signed pack does not saturate).
    const __m128i rg = _mm_unpacklo_epi32(k4[0], k4[1]);
    const __m128i ba = _mm_unpacklo_epi32(k4[2], k4[3]);
    const __m128i lo = _mm_sub_epi32(_mm_unpacklo_epi64(rg, ba), bias);
    const __m128i hi = _mm_sub_epi32(_mm_unpackhi_epi64(rg, ba), bias);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * i), _mm_xor_si128(_mm_packs_epi32(lo, hi), flip));
  }
  color_codes_scalar(q, c, scale, x0 + i, x_ref, n - i, out + 4 * i);
}
#else
void depth_codes(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale, std::uint32_t* out) {
  depth_codes_scalar(z, offset, x0, x_ref, n, scale, out);
}
void color_codes(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                 std::uint16_t* out) {
  color_codes_scalar(q, c, scale, x0, x_ref, n, out);
}
#endif

}  // namespace passim
