// The rasterizer's span kernels' SIMD forms (span_kernels.hpp): SSE2 (every x86-64 processor)
// and AVX2 (where the processor has it) for depth codes, colour codes and projective texture
// coordinates, each computing the scalar reference's IEEE operations in the same order
// (span_kernels.cpp), and the dispatch between them (stages/kernel_paths.hpp);
// tests/span_kernels_test.cpp compares them bit for bit.
#include "stages/kernel_paths.hpp"
#include "stages/span_kernels.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#ifndef PASSIM_HAVE_AVX2_KERNEL
#define PASSIM_HAVE_AVX2_KERNEL 1
#endif
#endif

namespace passim {

#if defined(PASSIM_HAVE_AVX2_KERNEL)
namespace {
__attribute__((target("avx2"))) void texture_coordinates_avx2(const SpanPlane stq[4], int x0, double x_ref, int n,
                                                              int used, double* s, double* t, double* r) {
  const __m256d half = _mm256_set1_pd(0.5), ref = _mm256_set1_pd(x_ref);
  __m256d row[4], d[4];
  for (int k = 0; k < 4; ++k) {
    row[k] = _mm256_set1_pd(stq[k].row);
    d[k] = _mm256_set1_pd(stq[k].d_dx);
  }
  double* out[3] = {s, t, r};
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    const __m256d xs = _mm256_cvtepi32_pd(_mm_setr_epi32(x0 + i, x0 + i + 1, x0 + i + 2, x0 + i + 3));
    const __m256d dx = _mm256_sub_pd(_mm256_add_pd(xs, half), ref);
    const __m256d q = _mm256_add_pd(row[3], _mm256_mul_pd(d[3], dx));
    for (int k = 0; k < 3; ++k)
      _mm256_storeu_pd(out[k] + i, k < used ? _mm256_div_pd(_mm256_add_pd(row[k], _mm256_mul_pd(d[k], dx)), q)
                                            : _mm256_setzero_pd());
  }
  texture_coordinates_scalar(stq, x0 + i, x_ref, n - i, used, s + i, t + i, r + i);
}
}  // namespace

void texture_coordinates(const SpanPlane stq[4], int x0, double x_ref, int n, int used, double* s, double* t,
                         double* r) {
  if (use_avx2()) return texture_coordinates_avx2(stq, x0, x_ref, n, used, s, t, r);
  texture_coordinates_scalar(stq, x0, x_ref, n, used, s, t, r);
}

namespace {
// AVX2: four fragments at a time, the same operations as the scalar reference (no FMA:
// each multiply and add is its own instruction, and -ffp-contract=off forbids fusing them).
// `padded`: the last group of four is computed whole even past n (the caller's buffer
// has room); lanes are independent, so the first n codes are the same.
__attribute__((target("avx2"))) void color_codes_avx2(const SpanPlane& q, const SpanPlane c[4], const double scale[4],
                                                      int x0, double x_ref, int n, std::uint16_t* out,
                                                      bool padded = false) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
  const __m256d q_row = _mm256_set1_pd(q.row), q_d = _mm256_set1_pd(q.d_dx);
  const __m256d ref = _mm256_set1_pd(x_ref);
  __m256d c_row[4], c_d[4], s[4];
  for (int k = 0; k < 4; ++k) {
    c_row[k] = _mm256_set1_pd(c[k].row);
    c_d[k] = _mm256_set1_pd(c[k].d_dx);
    s[k] = _mm256_set1_pd(scale[k]);
  }
  const __m128i bias = _mm_set1_epi32(32768), flip = _mm_set1_epi16(static_cast<short>(0x8000));
  int i = 0;
  for (; padded ? i < n : i + 4 <= n; i += 4) {
    const __m256d xs = _mm256_cvtepi32_pd(_mm_setr_epi32(x0 + i, x0 + i + 1, x0 + i + 2, x0 + i + 3));
    const __m256d dx = _mm256_sub_pd(_mm256_add_pd(xs, half), ref);
    const __m256d inv_q = _mm256_div_pd(one, _mm256_add_pd(q_row, _mm256_mul_pd(q_d, dx)));
    __m128i k4[4];
    for (int k = 0; k < 4; ++k) {
      __m256d v = _mm256_mul_pd(_mm256_add_pd(c_row[k], _mm256_mul_pd(c_d[k], dx)), inv_q);
      v = _mm256_min_pd(_mm256_max_pd(v, zero), one);  // NaN -> 0 as MAXPD returns the second operand
      k4[k] = _mm256_cvttpd_epi32(_mm256_add_pd(_mm256_mul_pd(v, s[k]), half));
    }
    // k4[k] = channel k of fragments 0..3; transpose to r g b a per fragment, then pack.
    const __m128i rg_lo = _mm_unpacklo_epi32(k4[0], k4[1]), rg_hi = _mm_unpackhi_epi32(k4[0], k4[1]);
    const __m128i ba_lo = _mm_unpacklo_epi32(k4[2], k4[3]), ba_hi = _mm_unpackhi_epi32(k4[2], k4[3]);
    const __m128i f0 = _mm_sub_epi32(_mm_unpacklo_epi64(rg_lo, ba_lo), bias);
    const __m128i f1 = _mm_sub_epi32(_mm_unpackhi_epi64(rg_lo, ba_lo), bias);
    const __m128i f2 = _mm_sub_epi32(_mm_unpacklo_epi64(rg_hi, ba_hi), bias);
    const __m128i f3 = _mm_sub_epi32(_mm_unpackhi_epi64(rg_hi, ba_hi), bias);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * i), _mm_xor_si128(_mm_packs_epi32(f0, f1), flip));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 4 * i + 8), _mm_xor_si128(_mm_packs_epi32(f2, f3), flip));
  }
  if (!padded) color_codes_scalar(q, c, scale, x0 + i, x_ref, n - i, out + 4 * i);
}

__attribute__((target("avx2"))) void depth_codes_avx2(const SpanPlane& z, double offset, int x0, double x_ref, int n,
                                                      double scale, std::uint32_t* out, bool padded = false) {
  const __m256d zero = _mm256_setzero_pd(), one = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
  const __m256d row = _mm256_set1_pd(z.row), d = _mm256_set1_pd(z.d_dx), off = _mm256_set1_pd(offset);
  const __m256d s = _mm256_set1_pd(scale), ref = _mm256_set1_pd(x_ref);
  int i = 0;
  for (; padded ? i < n : i + 4 <= n; i += 4) {
    const __m256d xs = _mm256_cvtepi32_pd(_mm_setr_epi32(x0 + i, x0 + i + 1, x0 + i + 2, x0 + i + 3));
    const __m256d dx = _mm256_sub_pd(_mm256_add_pd(xs, half), ref);
    __m256d v = _mm256_add_pd(_mm256_add_pd(row, _mm256_mul_pd(d, dx)), off);
    v = _mm256_min_pd(_mm256_max_pd(v, zero), one);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm256_cvttpd_epi32(_mm256_add_pd(_mm256_mul_pd(v, s), half)));
  }
  if (!padded) depth_codes_scalar(z, offset, x0 + i, x_ref, n - i, scale, out + i);
}
}  // namespace
bool depth_codes_has_avx2() { return __builtin_cpu_supports("avx2"); }
void depth_codes_wide(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                      std::uint32_t* out) {
  if (scale >= 2147483647.0) return depth_codes_scalar(z, offset, x0, x_ref, n, scale, out);
  depth_codes_avx2(z, offset, x0, x_ref, n, scale, out);
}
bool color_codes_has_avx2() { return __builtin_cpu_supports("avx2"); }
void color_codes_wide(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                      std::uint16_t* out) {
  color_codes_avx2(q, c, scale, x0, x_ref, n, out);
}
void depth_codes_padded(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                        std::uint32_t* out) {
  if (!use_avx2() || scale >= 2147483647.0) return depth_codes(z, offset, x0, x_ref, n, scale, out);
  depth_codes_avx2(z, offset, x0, x_ref, n, scale, out, true);
}
void color_codes_padded(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                        std::uint16_t* out) {
  if (!use_avx2()) return color_codes(q, c, scale, x0, x_ref, n, out);
  color_codes_avx2(q, c, scale, x0, x_ref, n, out, true);
}
#else
void texture_coordinates(const SpanPlane stq[4], int x0, double x_ref, int n, int used, double* s, double* t,
                         double* r) {
  texture_coordinates_scalar(stq, x0, x_ref, n, used, s, t, r);
}
void depth_codes_padded(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                        std::uint32_t* out) {
  depth_codes(z, offset, x0, x_ref, n, scale, out);
}
void color_codes_padded(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                        std::uint16_t* out) {
  color_codes(q, c, scale, x0, x_ref, n, out);
}
bool color_codes_has_avx2() { return false; }
void color_codes_wide(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                      std::uint16_t* out) {
  color_codes_scalar(q, c, scale, x0, x_ref, n, out);
}
bool depth_codes_has_avx2() { return false; }
void depth_codes_wide(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                      std::uint32_t* out) {
  depth_codes_scalar(z, offset, x0, x_ref, n, scale, out);
}
#endif

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
  // 31-32 bits, or the reference asked for: the scalar loop.
  if (scale >= 2147483647.0 || !use_sse2()) return depth_codes_scalar(z, offset, x0, x_ref, n, scale, out);
  if (use_avx2() && n >= 4) return depth_codes_wide(z, offset, x0, x_ref, n, scale, out);
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
  if (!use_sse2()) return color_codes_scalar(q, c, scale, x0, x_ref, n, out);
  if (use_avx2() && n >= 4) return color_codes_wide(q, c, scale, x0, x_ref, n, out);
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
