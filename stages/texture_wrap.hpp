// The wrap modes, nearest texel and linear weights of OpenGL 1.2.1 §3.8.4-3.8.5, shared by
// texture sampling's reference (texture_sample.cpp) and its fast paths
// (texture_sample_fast.cpp): one expression each, so both give the same bits.
#pragma once
#include <algorithm>

#include "pipeline/fixed_point.hpp"
#include "pipeline/gl.hpp"

namespace passim {

// §3.8.4 wrap applied to a coordinate before scaling; `edge` = 1/(2·size), CLAMP_TO_EDGE's limit.
inline double wrap_coordinate(double s, GLenum mode, double edge) {
  switch (mode) {
    case GL_REPEAT: return s - floor_exact(s);
    case GL_CLAMP_TO_EDGE: return std::clamp(s, edge, 1.0 - edge);
    default: return std::clamp(s, 0.0, 1.0);  // GL_CLAMP
  }
}
inline double edge_of(int size) { return 1.0 / (2.0 * size); }
inline double wrap_coordinate(double s, GLenum mode, int size) { return wrap_coordinate(s, mode, edge_of(size)); }

inline int wrap_index(int i, GLenum mode, int size) {
  if (mode == GL_REPEAT) {
    int m = i % size;
    return m < 0 ? m + size : m;
  }
  return i;  // CLAMP may reach the border (or border colour); CLAMP_TO_EDGE cannot leave [0, size)
}

// eq. 3.17: (1−α)τ0 + ατ1; eq. 3.18: (1−α)(1−β)τ00 + α(1−β)τ10 + (1−α)βτ01 + αβτ11, with A11's exact
// real weights — one expression for the general and the fast path, so the same bits.
inline double lerp_1d(double alpha, double a, double b) { return (1.0 - alpha) * a + alpha * b; }
inline double lerp_2d(double alpha, double beta, double t00, double t10, double t01, double t11) {
  return (1.0 - alpha) * (1.0 - beta) * t00 + alpha * (1.0 - beta) * t10 + (1.0 - alpha) * beta * t01 +
         alpha * beta * t11;
}

// §3.8.5: i = floor(u), with s = 1 giving W − 1.
inline int nearest_index(double s, GLenum mode, double edge, int size) {
  const double u = wrap_coordinate(s, mode, edge) * size;
  return wrap_index(std::min(static_cast<int>(floor_exact(u)), size - 1), mode, size);
}

}  // namespace passim
