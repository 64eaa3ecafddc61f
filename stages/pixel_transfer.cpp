#include "stages/pixel_transfer.hpp"

#include "pipeline/fixed_point.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "stages/avx2.hpp"
#include "stages/kernel_paths.hpp"

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
  if (s.removed.convolution) return nullptr;
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

TransferPlan plan_transfer(const PixelTransferState& s, const Mat4& m) {
  TransferPlan plan;
  plan.state = &s;
  plan.matrix = &m;
  plan.scale_bias = s.scale != Vec4(1.0) || s.bias != Vec4(0.0);
  plan.map_color = s.map_color;
  plan.color_matrix = !s.removed.color_matrix && (m != Mat4(1.0) || s.post_color_matrix_scale != Vec4(1.0) ||
                                                  s.post_color_matrix_bias != Vec4(0.0));
  for (std::size_t t = 0; t < 3; ++t)
    plan.tables[t] =
        !s.removed.color_tables && s.tables[t].enabled && !s.tables[t].entries.empty() ? &s.tables[t] : nullptr;
  return plan;
}

void transfer_pre_convolution_scalar(const TransferPlan& plan, Rgba* pixels, std::size_t n) {
  const PixelTransferState& s = *plan.state;
  for (std::size_t i = 0; i < n; ++i) {
    Rgba& p = pixels[i];
    // Step 2: c = c·scale + bias, no clamp.
    if (plan.scale_bias)
      for (int k = 0; k < 4; ++k) p[static_cast<std::size_t>(k)] = p[static_cast<std::size_t>(k)] * s.scale[k] + s.bias[k];
    // Step 3: MAP_COLOR — clamp, index round(c·(size − 1)), replace by the map's entry.
    if (plan.map_color)
      for (std::size_t k = 0; k < 4; ++k) {
        const std::vector<double>& map = s.color_maps[k];
        const double v = clamp_nan_low(p[k], 0.0, 1.0);
        p[k] = map[static_cast<std::size_t>(v * static_cast<double>(map.size() - 1) + 0.5)];
      }
    // Step 4: COLOR_TABLE.
    if (plan.tables[kColorTable]) color_table_lookup(*plan.tables[kColorTable], p);
  }
}

void transfer_post_convolution_scalar(const TransferPlan& plan, Rgba* pixels, std::size_t n) {
  const PixelTransferState& s = *plan.state;
  for (std::size_t i = 0; i < n; ++i) {
    Rgba& p = pixels[i];
    // Step 6: POST_CONVOLUTION_COLOR_TABLE. Step 7: colour matrix with its post scale and bias.
    if (plan.tables[kPostConvolutionTable]) color_table_lookup(*plan.tables[kPostConvolutionTable], p);
    if (plan.color_matrix) {
      const Vec4 r = *plan.matrix * Vec4(p[0], p[1], p[2], p[3]);
      for (int k = 0; k < 4; ++k)
        p[static_cast<std::size_t>(k)] = r[k] * s.post_color_matrix_scale[k] + s.post_color_matrix_bias[k];
    }
    // Step 8: POST_COLOR_MATRIX_COLOR_TABLE.
    if (plan.tables[kPostColorMatrixTable]) color_table_lookup(*plan.tables[kPostColorMatrixTable], p);
  }
}

void color_codes_from_reals_scalar(const Rgba* pixels, std::size_t n, const double max[4], std::uint16_t* out) {
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 4; ++k)
      out[4 * i + k] = static_cast<std::uint16_t>(clamp_nan_low(pixels[i][k], 0.0, 1.0) * max[k] + 0.5);
}

void color_codes_from_reals(const Rgba* pixels, std::size_t n, const double max[4], std::uint16_t* out) {
  (use_avx2() ? color_codes_from_reals_avx2 : color_codes_from_reals_scalar)(pixels, n, max, out);
}

bool transfer_per_component(const PixelTransferState& s, const Mat4& m, int dims) {
  return !active_convolution(s, dims) && !plan_transfer(s, m).color_matrix && !s.histogram.enabled &&
         !s.minmax.enabled;
}

void transfer_per_pixel_steps(const PixelTransferState& s, const Mat4& m, Rgba* pixels, std::size_t n) {
  // The kernels transfer_rgba chooses (the scalar and AVX2 ones agree bit for bit).
  const TransferPlan plan = plan_transfer(s, m);
  const bool wide = use_avx2();
  (wide && !plan.map_color ? transfer_pre_convolution_avx2 : transfer_pre_convolution_scalar)(plan, pixels, n);
  (wide ? transfer_post_convolution_avx2 : transfer_post_convolution_scalar)(plan, pixels, n);
}

void count_transfer(const PixelTransferState& s, const Mat4& m, std::uint64_t n_in, std::uint64_t n_out,
                    Counters& counters) {
  const TransferPlan plan = plan_transfer(s, m);
  if (plan.scale_bias) counters.pixels_scale_bias += n_in;
  if (s.map_color) counters.pixels_mapped += n_in;
  if (plan.tables[kColorTable]) counters.color_table_lookups += n_in;
  if (plan.color_matrix) counters.pixels_color_matrix += n_out;
  if (plan.tables[kPostConvolutionTable]) counters.post_convolution_table_lookups += n_out;
  if (plan.tables[kPostColorMatrixTable]) counters.post_color_matrix_table_lookups += n_out;
  counters.pixels_transferred += n_in;
}

bool transfer_rgba(std::vector<Rgba>& pixels, int& width, int& height, PixelTransferState& s, const Mat4& m,
                   Counters& counters, int dims, std::vector<Rgba>* spare, const RowSplitter* split) {
  const TransferPlan plan = plan_transfer(s, m);
  const bool wide = use_avx2();
  const std::uint64_t n_in = pixels.size();
  // Per-pixel work over the current image's rows, split as `split` chooses.
  auto by_rows = [&](auto&& per_pixels) {
    const std::size_t w = static_cast<std::size_t>(std::max(width, 0));
    const auto rows = [&](int first, int end) {
      per_pixels(pixels.data() + w * static_cast<std::size_t>(first), w * static_cast<std::size_t>(end - first));
    };
    if (split && w > 0 && pixels.size() == w * static_cast<std::size_t>(std::max(height, 0))) (*split)(height, rows);
    else per_pixels(pixels.data(), pixels.size());
  };
  const auto pre = wide && !plan.map_color ? transfer_pre_convolution_avx2 : transfer_pre_convolution_scalar;
  by_rows([&](Rgba* p, std::size_t n) { pre(plan, p, n); });
  // Step 5: convolution, then the post-convolution scale and bias (only when a convolution
  // ran, A14). No clamp between convolution and the colour matrix.
  const ConvolutionFilter* filter = active_convolution(s, dims);
  if (filter) {
    convolve(pixels, width, height, *filter, counters, ConvolutionKernel::Fastest, spare, split);
    by_rows([&](Rgba* p, std::size_t n) {
      for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 4; ++k)
          p[i][static_cast<std::size_t>(k)] =
              p[i][static_cast<std::size_t>(k)] * s.post_convolution_scale[k] + s.post_convolution_bias[k];
    });
  }
  const auto post = wide ? transfer_post_convolution_avx2 : transfer_post_convolution_scalar;
  by_rows([&](Rgba* p, std::size_t n) { post(plan, p, n); });
  const std::uint64_t n = pixels.size();
  count_transfer(s, m, n_in, n, counters);
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

void transfer_stencil(std::vector<double>& indices, const PixelTransferState& s, Counters& counters) {
  const std::vector<double>& map = s.other_maps[GL_PIXEL_MAP_S_TO_S - GL_PIXEL_MAP_I_TO_I];
  const int map_bits = std::countr_zero(map.size());  // the size is a power of two
  for (double& index : indices) {
    index = std::ldexp(index, s.index_shift) + static_cast<double>(s.index_offset);
    if (s.map_stencil) index = map[index_low_bits(index, map_bits)];
  }
  if (s.map_stencil) counters.pixels_mapped += indices.size();
}

void transfer_depth(std::vector<double>& depth, const PixelTransferState& s) {
  if (s.depth_scale == 1.0 && s.depth_bias == 0.0) return;
  for (double& d : depth) d = d * s.depth_scale + s.depth_bias;
}

}  // namespace passim
