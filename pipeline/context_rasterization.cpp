// Context: the rasterization state of points, lines and polygons (§3.3-3.5).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/clipping.hpp"
#include "stages/lighting.hpp"
#include "stages/rasterizer.hpp"

namespace passim {

// ---------------------------------------------------------------- rasterization state (§3.3-3.5)

void Context::glCullFace(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (mode != GL_FRONT && mode != GL_BACK && mode != GL_FRONT_AND_BACK) return set_error(GL_INVALID_ENUM);
  polygon_.cull_face = mode;
}

void Context::glFrontFace(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (mode != GL_CW && mode != GL_CCW) return set_error(GL_INVALID_ENUM);
  polygon_.front_face = mode;
}

void Context::glPolygonMode(GLenum face, GLenum mode) {
  PASSIM_ENTRY(face, mode)
  if (face != GL_FRONT && face != GL_BACK && face != GL_FRONT_AND_BACK) return set_error(GL_INVALID_ENUM);
  if (mode != GL_POINT && mode != GL_LINE && mode != GL_FILL) return set_error(GL_INVALID_ENUM);
  if (face != GL_BACK) polygon_.mode_front = mode;
  if (face != GL_FRONT) polygon_.mode_back = mode;
}

void Context::glPolygonOffset(GLfloat factor, GLfloat units) {
  PASSIM_ENTRY(factor, units)
  polygon_.offset_factor = factor;
  polygon_.offset_units = units;
}

void Context::glPointSize(GLfloat size) {
  PASSIM_ENTRY(size)
  if (!(size > 0.0f)) return set_error(GL_INVALID_VALUE);
  polygon_.point_size = size;
}

void Context::glLineWidth(GLfloat width) {
  PASSIM_ENTRY(width)
  if (!(width > 0.0f)) return set_error(GL_INVALID_VALUE);
  polygon_.line_width = width;
}

void Context::glLineStipple(GLint factor, GLushort pattern) {
  PASSIM_ENTRY(factor, pattern)
  // §3.4.2: the factor is clamped to [1, 256].
  polygon_.stipple_repeat = std::clamp(factor, 1, 256);
  polygon_.stipple_pattern = pattern;
}

}  // namespace passim
