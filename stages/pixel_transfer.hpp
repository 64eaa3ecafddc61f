// Pixel transfer (OpenGL 1.2.1 §3.6.5, ARB_imaging), in the spec's order. Modelled so far:
// RGBA scale and bias, the colour matrix with its post scale and bias, depth scale and bias.
// No clamp anywhere in between (clamping happens at the final conversion).
#pragma once
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/state.hpp"
#include "stages/pixel_unpack.hpp"

namespace passim {

// Table 6.17 (pixel transfer).
struct PixelTransferState {
  Vec4 scale{1.0, 1.0, 1.0, 1.0}, bias{0.0, 0.0, 0.0, 0.0};
  double depth_scale = 1.0, depth_bias = 0.0;
  bool map_color = false, map_stencil = false;
  int index_shift = 0, index_offset = 0;
  Vec4 post_color_matrix_scale{1.0, 1.0, 1.0, 1.0}, post_color_matrix_bias{0.0, 0.0, 0.0, 0.0};
};

// Applies the RGBA transfer operations to every group, in place.
void transfer_rgba(std::vector<Rgba>& pixels, const PixelTransferState& state, const Mat4& color_matrix,
                   Counters& counters);
void transfer_depth(std::vector<double>& depth, const PixelTransferState& state);

}  // namespace passim
