// The accumulation buffer's AVX2 row kernels (§4.2.4, A21): ACCUM/LOAD/ADD/MULT and RETURN on
// four pixels at a time, in the same operations and order as the scalar rows of accumulate.cpp,
// which are the reference; accumulate() chooses (stages/kernel_paths.hpp) and
// tests/accumulation_test.cpp compares them bit for bit.
#include "pipeline/fixed_point.hpp"
#include "stages/accumulate.hpp"
#include "stages/avx2.hpp"

namespace passim {

// ---------------------------------------------------------------- AVX2

#if defined(PASSIM_HAVE_AVX2_KERNEL)
namespace {

template <GLenum Op>
__attribute__((target("avx2"))) void accumulate_row_avx2_op(const AccumRowOp& s, std::int32_t* acc,
                                                            const std::uint16_t* read, int n) {
  const __m256d scale = _mm256_set1_pd(s.scale), value = _mm256_set1_pd(s.value);
  const __m256d lo = _mm256_set1_pd(-1.0), hi = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
  for (int i = 0; i < n; ++i) {
    __m128i* p = reinterpret_cast<__m128i*>(acc + 4 * i);
    __m256d result;
    if constexpr (Op == GL_LOAD || Op == GL_ACCUM) {
      const std::uint16_t* c = read + 4 * i;
      const __m256d term = _mm256_set_pd(s.term[3][c[3] & s.code_mask[3]], s.term[2][c[2] & s.code_mask[2]],
                                         s.term[1][c[1] & s.code_mask[1]], s.term[0][c[0] & s.code_mask[0]]);
      if constexpr (Op == GL_LOAD) {
        result = term;
      } else {
        result = _mm256_add_pd(_mm256_div_pd(_mm256_cvtepi32_pd(_mm_loadu_si128(p)), scale), term);
      }
    } else {
      const __m256d a = _mm256_div_pd(_mm256_cvtepi32_pd(_mm_loadu_si128(p)), scale);
      result = Op == GL_ADD ? _mm256_add_pd(a, value) : _mm256_mul_pd(a, value);
    }
    // floor is exact, as round_half_up's floor_exact; the result lies in ±(scale + ½).
    const __m256d rounded = _mm256_floor_pd(_mm256_add_pd(_mm256_mul_pd(clamp_nan_low_4(result, lo, hi), scale), half));
    _mm_storeu_si128(p, _mm256_cvttpd_epi32(rounded));
  }
}

}  // namespace

void accumulate_row_avx2(const AccumRowOp& s, std::int32_t* acc, const std::uint16_t* read, int n) {
  switch (s.op) {
    case GL_ACCUM: return accumulate_row_avx2_op<GL_ACCUM>(s, acc, read, n);
    case GL_LOAD: return accumulate_row_avx2_op<GL_LOAD>(s, acc, read, n);
    case GL_ADD: return accumulate_row_avx2_op<GL_ADD>(s, acc, read, n);
    default: return accumulate_row_avx2_op<GL_MULT>(s, acc, read, n);
  }
}

__attribute__((target("avx2"))) void return_row_avx2(const AccumRowOp& s, const std::int32_t* acc, std::uint16_t* out,
                                                     int n) {
  const __m256d scale = _mm256_set1_pd(s.scale), value = _mm256_set1_pd(s.value);
  const __m256d lo = _mm256_setzero_pd(), hi = _mm256_set1_pd(1.0), half = _mm256_set1_pd(0.5);
  const __m256d color_max = _mm256_loadu_pd(s.color_max);
  for (int i = 0; i < n; ++i) {
    const __m256d a = _mm256_div_pd(_mm256_cvtepi32_pd(_mm_loadu_si128(reinterpret_cast<const __m128i*>(acc + 4 * i))), scale);
    const __m256d v = _mm256_mul_pd(value, a);
    // The argument is >= 0.5, so truncation is the floor (as in float_to_fixed).
    const __m128i codes = _mm256_cvttpd_epi32(_mm256_add_pd(_mm256_mul_pd(clamp_nan_low_4(v, lo, hi), color_max), half));
    // Codes are below 2^16: pack the four 32-bit lanes to 16 bits without saturation effects.
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 4 * i), _mm_packus_epi32(codes, codes));
  }
}

#else
void accumulate_row_avx2(const AccumRowOp& s, std::int32_t* acc, const std::uint16_t* read, int n) {
  accumulate_row_scalar(s, acc, read, n);
}
void return_row_avx2(const AccumRowOp& s, const std::int32_t* acc, std::uint16_t* out, int n) {
  return_row_scalar(s, acc, out, n);
}
#endif

}  // namespace passim
