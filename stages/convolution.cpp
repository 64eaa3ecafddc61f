#include "stages/convolution.hpp"

#include <algorithm>

#include "stages/kernel_paths.hpp"

namespace passim {



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
