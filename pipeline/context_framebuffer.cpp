// Context: framebuffer control (§4.2): the buffers drawn and read, write masks, clears and
// the accumulation buffer.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/accumulate.hpp"
#include "stages/clear.hpp"

namespace passim {

// ---------------------------------------------------------------- framebuffer control (§4.2)

std::vector<ColorBufferId> Context::buffers_named(GLenum mode) const {
  const bool dbl = fb_.config.double_buffer;
  switch (mode) {
    case GL_FRONT: case GL_FRONT_LEFT: case GL_LEFT: return {ColorBufferId::FrontLeft};
    case GL_BACK: case GL_BACK_LEFT:
      if (dbl) return {ColorBufferId::BackLeft};
      return {};
    case GL_FRONT_AND_BACK:
      if (dbl) return {ColorBufferId::FrontLeft, ColorBufferId::BackLeft};
      return {ColorBufferId::FrontLeft};
    default: return {};
  }
}

namespace {
bool is_buffer_enum(GLenum mode) {
  switch (mode) {
    case GL_NONE: case GL_FRONT_LEFT: case GL_FRONT_RIGHT: case GL_BACK_LEFT: case GL_BACK_RIGHT: case GL_FRONT:
    case GL_BACK: case GL_LEFT: case GL_RIGHT: case GL_FRONT_AND_BACK: return true;
    default: return mode >= GL_AUX0 && mode < GL_AUX0 + 4;
  }
}
}  // namespace

void Context::glDrawBuffer(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (!is_buffer_enum(mode)) return set_error(GL_INVALID_ENUM);
  std::vector<ColorBufferId> ids = buffers_named(mode);
  if (mode != GL_NONE && ids.empty()) return set_error(GL_INVALID_OPERATION);  // names no existing buffer
  fb_control_.draw_buffer = mode;
  draw_buffer_ids_ = std::move(ids);
}

void Context::glReadBuffer(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (!is_buffer_enum(mode) || mode == GL_NONE || mode == GL_FRONT_AND_BACK) return set_error(GL_INVALID_ENUM);
  if (buffers_named(mode).empty()) return set_error(GL_INVALID_OPERATION);
  pixel_.read_buffer = mode;
}

const ColorPlane* Context::color_buffer(GLenum which) const {
  std::vector<ColorBufferId> ids = buffers_named(which);
  if (ids.empty()) return nullptr;
  return &fb_.color[static_cast<int>(ids.front())];
}

void Context::glClear(GLbitfield mask) {
  PASSIM_ENTRY(mask)
  const GLbitfield known = GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT | GL_ACCUM_BUFFER_BIT;
  if (mask & ~known) return set_error(GL_INVALID_VALUE);
  clear_buffers(mask, fb_control_, fragment_, draw_buffer_ids_, fb_, counters(), rows_on_lanes());
}

void Context::glClearColor(GLfloat r, GLfloat g, GLfloat b, GLfloat a) {
  PASSIM_ENTRY(r, g, b, a)
  fb_control_.clear_color = Vec4(clamp_nan_low(r, 0, 1), clamp_nan_low(g, 0, 1), clamp_nan_low(b, 0, 1),
                                 clamp_nan_low(a, 0, 1));
}

void Context::glClearDepth(GLdouble depth) {
  PASSIM_ENTRY(depth)
  fb_control_.clear_depth = clamp_nan_low(depth, 0.0, 1.0);
}

void Context::glClearStencil(GLint s) {
  PASSIM_ENTRY(s)
  fb_control_.clear_stencil = s;
}

void Context::glClearAccum(GLfloat r, GLfloat g, GLfloat b, GLfloat a) {
  PASSIM_ENTRY(r, g, b, a)
  fb_control_.clear_accum = Vec4(clamp_nan_low(r, -1, 1), clamp_nan_low(g, -1, 1), clamp_nan_low(b, -1, 1),
                                 clamp_nan_low(a, -1, 1));
}

void Context::glAccum(GLenum op, GLfloat value) {
  PASSIM_ENTRY(op, value)
  if (op != GL_ACCUM && op != GL_LOAD && op != GL_RETURN && op != GL_MULT && op != GL_ADD)
    return set_error(GL_INVALID_ENUM);
  if (fb_.config.accum_bits == 0) return set_error(GL_INVALID_OPERATION);
  // §4.2.4: the whole window, or the scissor box when the scissor test is on.
  accumulate(op, value, scissored_window(fragment_, fb_.width(), fb_.height()), *color_buffer(pixel_.read_buffer), draw_buffer_ids_, fb_control_.color_mask, fb_,
             counters());
}

void Context::glColorMask(GLboolean r, GLboolean g, GLboolean b, GLboolean a) {
  PASSIM_ENTRY(r, g, b, a)
  fb_control_.color_mask = {r != GL_FALSE, g != GL_FALSE, b != GL_FALSE, a != GL_FALSE};
}

void Context::glDepthMask(GLboolean flag) {
  PASSIM_ENTRY(flag)
  fb_control_.depth_mask = flag != GL_FALSE;
}

void Context::glStencilMask(GLuint mask) {
  PASSIM_ENTRY(mask)
  fb_control_.stencil_writemask = mask;
}

}  // namespace passim
