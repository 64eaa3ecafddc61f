// A vertex after per-vertex operations (§2.10-2.13): what clipping and
// rasterization consume.
#pragma once
#include <array>
#include <cstdint>

#include "pipeline/state.hpp"

namespace passim {

struct ProcessedVertex {
  Vec4 clip{0.0, 0.0, 0.0, 1.0};  // clip coordinates
  Vec4 eye{0.0, 0.0, 0.0, 1.0};   // eye coordinates (user clip planes)
  std::array<Vec4, 2> color{};    // [front, back], clamped and quantised (A4)
  Vec4 tex{0.0, 0.0, 0.0, 1.0};   // after texgen and the texture matrix
  // Lighting inputs kept until the polygon's facing is known (colour not yet computed).
  Vec3 normal_eye{0.0};
  std::uint32_t material_index = 0;
  bool light_pending = false;
  // §2.6.2: whether the edge starting at this vertex is a boundary edge (polygon mode LINE, POINT).
  bool edge_flag = true;
};

}  // namespace passim
