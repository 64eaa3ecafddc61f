// Convolution's fast path: the AVX2 kernel for the output pixels whose footprint lies inside
// the image (§3.6.5 step 5), the same IEEE operations in the same order as the reference loop of
// convolution.cpp; convolve chooses (stages/kernel_paths.hpp) and
// tests/pixel_transfer_kernels_test.cpp compares them bit for bit for every filter size.
#include "stages/avx2.hpp"
#include "stages/convolution.hpp"

namespace passim {

#if defined(PASSIM_HAVE_AVX2_KERNEL)
// Output pixels (i, j), i in [i0, i1), whose whole footprint is inside the image: the sum
// over (m, n) in the reference's order, starting from +0, one multiply and one add per tap
// (no FMA); two pixels at a time so that their additions overlap. Components the filter
// does not convolve take the anchor pixel's value, as in the reference.
namespace {
__attribute__((target("avx2"))) inline void store_output(const InteriorRows& r, int j, int i, __m256d sum,
                                                         __m256d keep) {
  const __m256d anchor = _mm256_loadu_pd(r.image[static_cast<std::size_t>(j) * static_cast<std::size_t>(r.ws) + static_cast<std::size_t>(i)].data());
  _mm256_storeu_pd(r.out[static_cast<std::size_t>(j) * static_cast<std::size_t>(r.wo) + static_cast<std::size_t>(i)].data(),
                   _mm256_blendv_pd(sum, anchor, keep));
}

}  // namespace

__attribute__((target("avx2"))) void convolve_interior_avx2(const InteriorRows& r, int j, int i0, int i1) {
  const __m256d keep = _mm256_castsi256_pd(_mm256_setr_epi64x(r.conv[0] ? 0 : -1, r.conv[1] ? 0 : -1,
                                                              r.conv[2] ? 0 : -1, r.conv[3] ? 0 : -1));
  const std::size_t ws = static_cast<std::size_t>(r.ws), wf = static_cast<std::size_t>(r.wf);
  int i = i0;
  for (; i + 1 < i1; i += 2) {
    __m256d sum0 = _mm256_setzero_pd(), sum1 = _mm256_setzero_pd();
    for (int m = 0; m < r.hf; ++m) {
      const Rgba* s = r.image + static_cast<std::size_t>(j - r.ch + m) * ws + static_cast<std::size_t>(i - r.cw);
      const Rgba* t = r.taps + static_cast<std::size_t>(m) * wf;
      for (std::size_t n = 0; n < wf; ++n) {
        const __m256d tap = _mm256_loadu_pd(t[n].data());
        sum0 = _mm256_add_pd(sum0, _mm256_mul_pd(_mm256_loadu_pd(s[n].data()), tap));
        sum1 = _mm256_add_pd(sum1, _mm256_mul_pd(_mm256_loadu_pd(s[n + 1].data()), tap));
      }
    }
    store_output(r, j, i, sum0, keep);
    store_output(r, j, i + 1, sum1, keep);
  }
  for (; i < i1; ++i) {
    __m256d sum = _mm256_setzero_pd();
    for (int m = 0; m < r.hf; ++m) {
      const Rgba* s = r.image + static_cast<std::size_t>(j - r.ch + m) * ws + static_cast<std::size_t>(i - r.cw);
      const Rgba* t = r.taps + static_cast<std::size_t>(m) * wf;
      for (std::size_t n = 0; n < wf; ++n)
        sum = _mm256_add_pd(sum, _mm256_mul_pd(_mm256_loadu_pd(s[n].data()), _mm256_loadu_pd(t[n].data())));
    }
    store_output(r, j, i, sum, keep);
  }
}
#endif

}  // namespace passim
