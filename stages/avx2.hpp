// What the AVX2 row kernels share. Each kernel has a scalar reference beside it that performs
// the same IEEE operations in the same order, and a test that compares the two bit for bit;
// the kernel runs only where the processor has AVX2 (chosen at run time, so one binary serves
// every x86-64 machine with the same bits).
#pragma once

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define PASSIM_HAVE_AVX2_KERNEL 1
#endif

namespace passim {

inline bool cpu_has_avx2() {
#if defined(PASSIM_HAVE_AVX2_KERNEL)
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
#else
  return false;
#endif
}

#if defined(PASSIM_HAVE_AVX2_KERNEL)
// clamp_nan_low (fixed_point.hpp) on four lanes: when x is NaN, MAXPD returns its second
// operand, lo; equal values are the same value either way.
__attribute__((target("avx2"))) inline __m256d clamp_nan_low_4(__m256d x, __m256d lo, __m256d hi) {
  return _mm256_min_pd(_mm256_max_pd(x, lo), hi);
}
#endif

}  // namespace passim
