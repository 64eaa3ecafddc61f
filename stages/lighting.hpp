// Per-vertex lighting, OpenGL 1.2.1 §2.13.1 (equation in the "Lighting Operation" text).
#pragma once
#include "pipeline/state.hpp"

namespace passim {

struct LitColor {
  Vec4 primary;    // unclamped
  Vec3 secondary;  // specular part when LIGHT_MODEL_COLOR_CONTROL is SEPARATE_SPECULAR_COLOR, else 0
};

// The colour of a vertex at eye position `eye` (w != 0) with unit eye-space normal
// `normal` (already flipped for back faces), for material `m`.
LitColor light_vertex(const LightingState& lighting, const Material& m, const Vec4& eye, const Vec3& normal);

}  // namespace passim
