#include "stages/pixel_transfer.hpp"

#include "pipeline/fixed_point.hpp"

#include <algorithm>

namespace passim {

void color_table_lookup(const ColorTable& t, Rgba& c) {
  const std::size_t w = t.entries.size();
  if (w == 0) return;
  const double w1 = static_cast<double>(w - 1);
  auto at = [&](int k) {
    const double v = clamp_nan_low(c[static_cast<std::size_t>(k)], 0.0, 1.0);
    // round(v·(W − 1)) with ties up; the argument is >= 0.5, so truncation is the floor.
    return static_cast<std::size_t>(v * w1 + 0.5);
  };
  const std::size_t r = at(0), g = at(1), b = at(2), a = at(3);
  switch (t.base) {
    case GL_ALPHA: c[3] = t.entries[a][3]; break;
    case GL_LUMINANCE: c[0] = t.entries[r][0]; c[1] = t.entries[g][0]; c[2] = t.entries[b][0]; break;
    case GL_LUMINANCE_ALPHA:
      c[0] = t.entries[r][0]; c[1] = t.entries[g][0]; c[2] = t.entries[b][0]; c[3] = t.entries[a][3];
      break;
    case GL_INTENSITY:
      c[0] = t.entries[r][0]; c[1] = t.entries[g][0]; c[2] = t.entries[b][0]; c[3] = t.entries[a][0];
      break;
    case GL_RGB: c[0] = t.entries[r][0]; c[1] = t.entries[g][1]; c[2] = t.entries[b][2]; break;
    default:
      c[0] = t.entries[r][0]; c[1] = t.entries[g][1]; c[2] = t.entries[b][2]; c[3] = t.entries[a][3];
      break;
  }
}

const ConvolutionFilter* active_convolution(const PixelTransferState& s, int dims) {
  if (dims == 1) return s.convolution_1d ? &s.filter_1d : nullptr;
  if (s.convolution_2d) return &s.filter_2d;
  if (s.separable_2d) return &s.filter_separable;
  return nullptr;
}

void Minmax::reset() {
  const double big = 3.40282346638528859812e+38;  // FLT_MAX
  min = {big, big, big, big};
  max = {-big, -big, -big, -big};
}

bool transfer_rgba(std::vector<Rgba>& pixels, int& width, int& height, PixelTransferState& s, const Mat4& m,
                   Counters& counters, int dims) {
  const bool scale_bias = s.scale != Vec4(1.0) || s.bias != Vec4(0.0);
  const bool matrix = m != Mat4(1.0) || s.post_color_matrix_scale != Vec4(1.0) || s.post_color_matrix_bias != Vec4(0.0);
  const ColorTable& t0 = s.tables[kColorTable];
  const ColorTable& t1 = s.tables[kPostConvolutionTable];
  const ColorTable& t2 = s.tables[kPostColorMatrixTable];
  const bool use0 = t0.enabled && !t0.entries.empty(), use1 = t1.enabled && !t1.entries.empty();
  const bool use2 = t2.enabled && !t2.entries.empty();
  const std::uint64_t n_in = pixels.size();
  // Step 2: c = c·scale + bias, no clamp. Step 4: COLOR_TABLE.
  for (Rgba& p : pixels) {
    if (scale_bias)
      for (int k = 0; k < 4; ++k) p[static_cast<std::size_t>(k)] = p[static_cast<std::size_t>(k)] * s.scale[k] + s.bias[k];
    // Step 3: MAP_COLOR — clamp, index round(c·(size − 1)), replace by the map's entry.
    if (s.map_color)
      for (std::size_t k = 0; k < 4; ++k) {
        const std::vector<double>& map = s.color_maps[k];
        const double v = clamp_nan_low(p[k], 0.0, 1.0);
        p[k] = map[static_cast<std::size_t>(v * static_cast<double>(map.size() - 1) + 0.5)];
      }
    if (use0) color_table_lookup(t0, p);
  }
  // Step 5: convolution, then the post-convolution scale and bias (only when a convolution
  // ran, A14). No clamp between convolution and the colour matrix.
  const ConvolutionFilter* filter = active_convolution(s, dims);
  if (filter) {
    convolve(pixels, width, height, *filter, counters);
    for (Rgba& p : pixels)
      for (int k = 0; k < 4; ++k)
        p[static_cast<std::size_t>(k)] = p[static_cast<std::size_t>(k)] * s.post_convolution_scale[k] + s.post_convolution_bias[k];
  }
  for (Rgba& p : pixels) {
    // Step 6: POST_CONVOLUTION_COLOR_TABLE. Step 7: colour matrix with its post scale and bias.
    if (use1) color_table_lookup(t1, p);
    if (matrix) {
      const Vec4 r = m * Vec4(p[0], p[1], p[2], p[3]);
      for (int k = 0; k < 4; ++k)
        p[static_cast<std::size_t>(k)] = r[k] * s.post_color_matrix_scale[k] + s.post_color_matrix_bias[k];
    }
    // Step 8: POST_COLOR_MATRIX_COLOR_TABLE.
    if (use2) color_table_lookup(t2, p);
  }
  const std::uint64_t n = pixels.size();
  if (scale_bias) counters.pixels_scale_bias += n_in;
  if (s.map_color) counters.pixels_mapped += n_in;
  if (use0) counters.color_table_lookups += n_in;
  if (matrix) counters.pixels_color_matrix += n;
  if (use1) counters.post_convolution_table_lookups += n;
  if (use2) counters.post_color_matrix_table_lookups += n;
  counters.pixels_transferred += n_in;
  // Step 9: HISTOGRAM — index round(clamp(c, 0, 1)·(W − 1)) per component the format has;
  // counters saturate (A23). The pixels themselves are unchanged.
  Histogram& h = s.histogram;
  if (h.enabled && !h.counts.empty()) {
    const double w1 = static_cast<double>(h.counts.size() - 1);
    const bool has[4] = {h.base != GL_ALPHA, h.base == GL_RGB || h.base == GL_RGBA,
                         h.base == GL_RGB || h.base == GL_RGBA,
                         h.base == GL_ALPHA || h.base == GL_LUMINANCE_ALPHA || h.base == GL_RGBA};
    for (const Rgba& p : pixels)
      for (int k = 0; k < 4; ++k) {
        if (!has[k]) continue;
        const std::size_t i = static_cast<std::size_t>(round_half_up(clamp_nan_low(p[static_cast<std::size_t>(k)], 0.0, 1.0) * w1));
        std::uint32_t& c = h.counts[i][static_cast<std::size_t>(k)];
        if (c != 0xFFFFFFFFu) ++c;
      }
    counters.histogram_updates += n;
    if (h.sink) return false;
  }
  // Step 10: MINMAX — unclamped values.
  Minmax& mm = s.minmax;
  if (mm.enabled) {
    for (const Rgba& p : pixels)
      for (std::size_t k = 0; k < 4; ++k) {
        mm.min[k] = std::min(mm.min[k], p[k]);
        mm.max[k] = std::max(mm.max[k], p[k]);
      }
    counters.minmax_updates += n;
    if (mm.sink) return false;
  }
  return true;
}

void transfer_depth(std::vector<double>& depth, const PixelTransferState& s) {
  if (s.depth_scale == 1.0 && s.depth_bias == 0.0) return;
  for (double& d : depth) d = d * s.depth_scale + s.depth_bias;
}

}  // namespace passim
