// Helpers the Context's entry-point files share (pipeline/context_*.cpp): small rules of the
// spec that more than one state group applies. Not part of the Context's interface.
#pragma once
#include <cmath>
#include <limits>
#include <type_traits>

#include "pipeline/gl.hpp"
#include "pipeline/state.hpp"
#include "stages/clipping.hpp"
#include "stages/vertex.hpp"

namespace passim {

// §2.6.1: the primitive modes Begin, DrawArrays and DrawElements accept.
inline bool is_primitive_mode(GLenum mode) { return mode <= GL_POLYGON; }

// Table 2.6 (§2.13): a colour or normal component given as an integer of b bits becomes a
// real, unsigned c as c / (2^b − 1), signed c as (2c + 1) / (2^b − 1); a floating-point
// component is taken as it is. (Vertex and texture coordinates are converted directly.)
template <class T>
double normalized_component(T c) {
  if constexpr (std::is_floating_point_v<T>) {
    return static_cast<double>(c);
  } else {
    constexpr double largest = std::numeric_limits<std::make_unsigned_t<T>>::max();  // 2^b − 1
    if constexpr (std::is_signed_v<T>) return (2.0 * c + 1.0) / largest;
    else return c / largest;
  }
}

// The user clip planes enabled now (§2.11), as the clipper takes them.
inline ClipPlanes clip_planes_of(const TransformState& t) {
  ClipPlanes planes;
  planes.user = t.clip_plane;
  for (int k = 0; k < 6; ++k)
    if (t.clip_enabled[k]) planes.user_enabled |= 1u << k;
  return planes;
}

// A vertex whose clip and eye coordinates are all finite (a NaN or infinite one drops its
// primitive, counted as clipped out).
inline bool finite_vertex(const ProcessedVertex& v) {
  return std::isfinite(v.clip.x) && std::isfinite(v.clip.y) && std::isfinite(v.clip.z) && std::isfinite(v.clip.w) &&
         std::isfinite(v.eye.x) && std::isfinite(v.eye.y) && std::isfinite(v.eye.z) && std::isfinite(v.eye.w);
}

}  // namespace passim
