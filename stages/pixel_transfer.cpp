#include "stages/pixel_transfer.hpp"

namespace passim {

void transfer_rgba(std::vector<Rgba>& pixels, const PixelTransferState& s, const Mat4& m, Counters& counters) {
  const bool scale_bias = s.scale != Vec4(1.0) || s.bias != Vec4(0.0);
  const bool matrix = m != Mat4(1.0) || s.post_color_matrix_scale != Vec4(1.0) || s.post_color_matrix_bias != Vec4(0.0);
  for (Rgba& p : pixels) {
    // §3.6.5 step 2: c = c·scale + bias, no clamp.
    if (scale_bias)
      for (int k = 0; k < 4; ++k) p[static_cast<std::size_t>(k)] = p[static_cast<std::size_t>(k)] * s.scale[k] + s.bias[k];
    // Steps 7: colour matrix, then its post scale and bias (ARB_imaging).
    if (matrix) {
      const Vec4 c(p[0], p[1], p[2], p[3]);
      const Vec4 r = m * c;
      for (int k = 0; k < 4; ++k)
        p[static_cast<std::size_t>(k)] = r[k] * s.post_color_matrix_scale[k] + s.post_color_matrix_bias[k];
    }
  }
  const std::uint64_t n = pixels.size();
  if (scale_bias) counters.pixels_scale_bias += n;
  if (matrix) counters.pixels_color_matrix += n;
  counters.pixels_transferred += n;
}

void transfer_depth(std::vector<double>& depth, const PixelTransferState& s) {
  if (s.depth_scale == 1.0 && s.depth_bias == 0.0) return;
  for (double& d : depth) d = d * s.depth_scale + s.depth_bias;
}

}  // namespace passim
