#include "stages/convolution.hpp"

#include <algorithm>

#include "stages/avx2.hpp"
#include "stages/kernel_paths.hpp"

namespace passim {

namespace {

// The taps as each output component reads them (tap[n + m·wf][k] is the filter component
// that component k is multiplied by), and which components the filter convolves.
struct InteriorRows {
  const Rgba* image;
  int ws, wf, hf, cw, ch;
  const Rgba* taps;
  bool conv[4];
  Rgba* out;
  int wo;
};

#if defined(PASSIM_HAVE_AVX2_KERNEL)
// Output pixels (i, j), i in [i0, i1), whose whole footprint is inside the image: the sum
// over (m, n) in the reference's order, starting from +0, one multiply and one add per tap
// (no FMA); two pixels at a time so that their additions overlap. Components the filter
// does not convolve take the anchor pixel's value, as in the reference.
__attribute__((target("avx2"))) inline void store_output(const InteriorRows& r, int j, int i, __m256d sum,
                                                         __m256d keep) {
  const __m256d anchor = _mm256_loadu_pd(r.image[static_cast<std::size_t>(j) * static_cast<std::size_t>(r.ws) + static_cast<std::size_t>(i)].data());
  _mm256_storeu_pd(r.out[static_cast<std::size_t>(j) * static_cast<std::size_t>(r.wo) + static_cast<std::size_t>(i)].data(),
                   _mm256_blendv_pd(sum, anchor, keep));
}

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

}  // namespace


Rgba ConvolutionFilter::tap(int n, int m) const {
  if (separable) {
    // Cf[n, m] = Crow[n]·Ccol[m].
    const Rgba& r = row[static_cast<std::size_t>(n)];
    const Rgba& c = column[static_cast<std::size_t>(m)];
    return {r[0] * c[0], r[1] * c[1], r[2] * c[2], r[3] * c[3]};
  }
  return taps[static_cast<std::size_t>(n + m * width)];
}

void convolve(std::vector<Rgba>& image, int& width, int& height, const ConvolutionFilter& f, Counters& counters,
              ConvolutionKernel kernel, std::vector<Rgba>* spare, const RowSplitter* split) {
  const int ws = width, hs = height, wf = f.width, hf = f.height;
  const bool reduce = f.border_mode == GL_REDUCE;
  const int wo = reduce ? ws - wf + 1 : ws, ho = reduce ? hs - hf + 1 : hs;
  if (wo <= 0 || ho <= 0 || wf == 0 || hf == 0) {
    // A REDUCE to nothing gives a null image (no error); a zero-size filter gives C = 0.
    if (wo <= 0 || ho <= 0) {
      image.clear();
      width = std::max(0, wo);
      height = std::max(0, ho);
    } else {
      for (Rgba& p : image) p = {0, 0, 0, 0};
    }
    return;
  }
  // Table 3.14: which components the filter convolves.
  bool conv[4];
  switch (f.base) {
    case GL_ALPHA: conv[0] = conv[1] = conv[2] = false; conv[3] = true; break;
    case GL_LUMINANCE: case GL_RGB: conv[0] = conv[1] = conv[2] = true; conv[3] = false; break;
    default: conv[0] = conv[1] = conv[2] = conv[3] = true; break;  // LA, INTENSITY, RGBA
  }
  // The filter component used for each image component (L/I filters keep their value in [0]).
  int source[4] = {0, 1, 2, 3};
  if (f.base == GL_LUMINANCE || f.base == GL_LUMINANCE_ALPHA || f.base == GL_INTENSITY) source[0] = source[1] = source[2] = 0;
  if (f.base == GL_INTENSITY) source[3] = 0;
  const int cw = reduce ? 0 : wf / 2, ch = reduce ? 0 : hf / 2;
  auto at = [&](int x, int y) -> Rgba {
    if (x >= 0 && x < ws && y >= 0 && y < hs) return image[static_cast<std::size_t>(y * ws + x)];
    if (f.border_mode == GL_CONSTANT_BORDER)
      return {f.border_color.r, f.border_color.g, f.border_color.b, f.border_color.a};
    return image[static_cast<std::size_t>(std::clamp(y, 0, hs - 1) * ws + std::clamp(x, 0, ws - 1))];  // REPLICATE
  };
  // The taps once (a separable filter's row x column products), in (n, m) order.
  std::vector<Rgba> taps(static_cast<std::size_t>(wf) * static_cast<std::size_t>(hf));
  for (int m = 0; m < hf; ++m)
    for (int n = 0; n < wf; ++n) taps[static_cast<std::size_t>(n + m * wf)] = f.tap(n, m);
  std::vector<Rgba> local;
  std::vector<Rgba>& out = spare ? *spare : local;
  out.resize(static_cast<std::size_t>(wo) * static_cast<std::size_t>(ho));  // every element is written below
  // The output columns whose footprint lies inside the image: [i_in0, i_in1).
  const int i_in0 = std::min(cw, wo), i_in1 = std::max(i_in0, std::min(wo, ws - wf + cw + 1));
#if defined(PASSIM_HAVE_AVX2_KERNEL)
  const bool wide = kernel == ConvolutionKernel::Fastest && use_avx2();
  std::vector<Rgba> component_taps(taps.size());
  for (std::size_t t = 0; t < taps.size(); ++t)
    for (std::size_t k = 0; k < 4; ++k) component_taps[t][k] = taps[t][static_cast<std::size_t>(source[k])];
  const InteriorRows rows{image.data(), ws, wf, hf, cw, ch, component_taps.data(), {conv[0], conv[1], conv[2], conv[3]},
                          out.data(), wo};
#else
  const bool wide = false;
  (void)kernel;
#endif
  auto output_rows = [&](int first_row, int end_row) {
  for (int j = first_row; j < end_row; ++j)
    for (int i = 0; i < wo; ++i) {
      const bool row_inside = j - ch >= 0 && j - ch + hf <= hs;
#if defined(PASSIM_HAVE_AVX2_KERNEL)
      if (wide && row_inside && i == i_in0 && i_in1 > i_in0) {
        convolve_interior_avx2(rows, j, i_in0, i_in1);
        i = i_in1 - 1;
        continue;
      }
#endif
      double sum[4] = {0, 0, 0, 0};
      // Inside the image the source is read directly; near the edges through the border rule.
      const bool inside = i - cw >= 0 && i - cw + wf <= ws && row_inside;
      for (int m = 0; m < hf; ++m)
        for (int n = 0; n < wf; ++n) {
          const int x = i - cw + n, y = j - ch + m;
          const Rgba s = inside ? image[static_cast<std::size_t>(y * ws + x)] : at(x, y);
          const Rgba& t = taps[static_cast<std::size_t>(n + m * wf)];
          for (int k = 0; k < 4; ++k)
            if (conv[k]) sum[k] += s[static_cast<std::size_t>(k)] * t[static_cast<std::size_t>(source[k])];
        }
      // Components the filter does not list pass unchanged (from the output's anchor pixel).
      const Rgba anchor = at(i, j);
      Rgba& o = out[static_cast<std::size_t>(j * wo + i)];
      for (int k = 0; k < 4; ++k) o[static_cast<std::size_t>(k)] = conv[k] ? sum[k] : anchor[static_cast<std::size_t>(k)];
    }
  };
  if (split) (*split)(ho, output_rows);
  else output_rows(0, ho);
  counters.convolution_taps += static_cast<std::uint64_t>(wo) * static_cast<std::uint64_t>(ho) *
                               static_cast<std::uint64_t>(wf) * static_cast<std::uint64_t>(hf);
  counters.pixels_convolved += static_cast<std::uint64_t>(wo) * static_cast<std::uint64_t>(ho);
  image.swap(out);
  width = wo;
  height = ho;
}

}  // namespace passim
