// Context: coordinate transformation (§2.10): matrices and their stacks, the viewport, the
// depth range, user clip planes and the GLU matrix helpers.
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

// ---------------------------------------------------------------- matrices (§2.10.2)

std::vector<Mat4>& Context::current_stack() {
  switch (transform_.matrix_mode) {
    case GL_PROJECTION: return transform_.projection;
    case GL_TEXTURE: return transform_.texture;
    case GL_COLOR: return transform_.color;
    default: return transform_.modelview;
  }
}

void Context::mult_matrix(const Mat4& m) {
  current_stack().back() = current_stack().back() * m;
  normal_matrix_dirty_ = true;
}

namespace {
template <class T>
Mat4 matrix_from(const T* m) {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r[c][row] = static_cast<double>(m[4 * c + row]);
  return r;
}
}  // namespace

void Context::glViewport(GLint x, GLint y, GLsizei width, GLsizei height) {
  PASSIM_ENTRY(x, y, width, height)
  if (width < 0 || height < 0) return set_error(GL_INVALID_VALUE);
  // §2.10.1: width and height are silently clamped to MAX_VIEWPORT_DIMS.
  viewport_.x = x;
  viewport_.y = y;
  viewport_.width = std::min(width, profile_.limits.max_viewport_size);
  viewport_.height = std::min(height, profile_.limits.max_viewport_size);
}

void Context::glDepthRange(GLclampd near_val, GLclampd far_val) {
  PASSIM_ENTRY(near_val, far_val)
  viewport_.near_val = clamp_nan_low(near_val, 0.0, 1.0);
  viewport_.far_val = clamp_nan_low(far_val, 0.0, 1.0);
}

void Context::glMatrixMode(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (mode != GL_MODELVIEW && mode != GL_PROJECTION && mode != GL_TEXTURE && mode != GL_COLOR)
    return set_error(GL_INVALID_ENUM);
  transform_.matrix_mode = mode;
}

void Context::glLoadIdentity() {
  PASSIM_ENTRY()
  current_stack().back() = Mat4(1.0);
  normal_matrix_dirty_ = true;
}

void Context::glLoadMatrixf(const GLfloat* m) {
  PASSIM_ENTRY(m)
  current_stack().back() = matrix_from(m);
  normal_matrix_dirty_ = true;
}

void Context::glLoadMatrixd(const GLdouble* m) {
  PASSIM_ENTRY(m)
  current_stack().back() = matrix_from(m);
  normal_matrix_dirty_ = true;
}

void Context::glMultMatrixf(const GLfloat* m) {
  PASSIM_ENTRY(m)
  mult_matrix(matrix_from(m));
}

void Context::glMultMatrixd(const GLdouble* m) {
  PASSIM_ENTRY(m)
  mult_matrix(matrix_from(m));
}

void Context::glPushMatrix() {
  PASSIM_ENTRY()
  std::vector<Mat4>& stack = current_stack();
  const MachineLimits& lim = profile_.limits;
  int max = lim.max_modelview_stack;
  if (transform_.matrix_mode == GL_PROJECTION) max = lim.max_projection_stack;
  if (transform_.matrix_mode == GL_TEXTURE) max = lim.max_texture_stack;
  if (transform_.matrix_mode == GL_COLOR) max = lim.max_color_matrix_stack;
  if (static_cast<int>(stack.size()) >= max) return set_error(GL_STACK_OVERFLOW);
  stack.push_back(stack.back());
}

void Context::glPopMatrix() {
  PASSIM_ENTRY()
  std::vector<Mat4>& stack = current_stack();
  if (stack.size() <= 1) return set_error(GL_STACK_UNDERFLOW);
  stack.pop_back();
  normal_matrix_dirty_ = true;
}

void Context::glTranslatef(GLfloat x, GLfloat y, GLfloat z) {
  PASSIM_ENTRY(x, y, z)
  mult_matrix(glm::translate(Mat4(1.0), Vec3(x, y, z)));
}

void Context::glTranslated(GLdouble x, GLdouble y, GLdouble z) {
  PASSIM_ENTRY(x, y, z)
  mult_matrix(glm::translate(Mat4(1.0), Vec3(x, y, z)));
}

void Context::glRotatef(GLfloat angle, GLfloat x, GLfloat y, GLfloat z) {
  PASSIM_ENTRY(angle, x, y, z)
  if (x == 0.0f && y == 0.0f && z == 0.0f) return;  // no axis: no rotation (GLM would divide by 0)
  mult_matrix(glm::rotate(Mat4(1.0), glm::radians(static_cast<double>(angle)), Vec3(x, y, z)));
}

void Context::glRotated(GLdouble angle, GLdouble x, GLdouble y, GLdouble z) {
  PASSIM_ENTRY(angle, x, y, z)
  if (x == 0.0 && y == 0.0 && z == 0.0) return;
  mult_matrix(glm::rotate(Mat4(1.0), glm::radians(angle), Vec3(x, y, z)));
}

void Context::glScalef(GLfloat x, GLfloat y, GLfloat z) {
  PASSIM_ENTRY(x, y, z)
  mult_matrix(glm::scale(Mat4(1.0), Vec3(x, y, z)));
}

void Context::glScaled(GLdouble x, GLdouble y, GLdouble z) {
  PASSIM_ENTRY(x, y, z)
  mult_matrix(glm::scale(Mat4(1.0), Vec3(x, y, z)));
}

void Context::glFrustum(GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f) {
  PASSIM_ENTRY(l, r, b, t, n, f)
  if (n <= 0.0 || f <= 0.0 || l == r || b == t || n == f) return set_error(GL_INVALID_VALUE);
  mult_matrix(glm::frustum(l, r, b, t, n, f));
}

void Context::glOrtho(GLdouble l, GLdouble r, GLdouble b, GLdouble t, GLdouble n, GLdouble f) {
  PASSIM_ENTRY(l, r, b, t, n, f)
  if (l == r || b == t || n == f) return set_error(GL_INVALID_VALUE);
  mult_matrix(glm::ortho(l, r, b, t, n, f));
}

void Context::gluPerspective(GLdouble fovy, GLdouble aspect, GLdouble z_near, GLdouble z_far) {
  PASSIM_ENTRY(fovy, aspect, z_near, z_far)
  // GLU does nothing for degenerate arguments; so do we.
  if (z_near == z_far || aspect == 0.0 || std::sin(glm::radians(fovy) / 2.0) == 0.0) return;
  mult_matrix(glm::perspective(glm::radians(fovy), aspect, z_near, z_far));
}

void Context::gluLookAt(GLdouble ex, GLdouble ey, GLdouble ez, GLdouble cx, GLdouble cy, GLdouble cz, GLdouble ux,
                        GLdouble uy, GLdouble uz) {
  PASSIM_ENTRY(ex, ey, ez, cx, cy, cz, ux, uy, uz)
  mult_matrix(glm::lookAt(Vec3(ex, ey, ez), Vec3(cx, cy, cz), Vec3(ux, uy, uz)));
}

void Context::glClipPlane(GLenum plane, const GLdouble* equation) {
  PASSIM_ENTRY(plane, equation)
  if (plane < GL_CLIP_PLANE0 || plane >= GL_CLIP_PLANE0 + 6) return set_error(GL_INVALID_ENUM);
  // §2.11: the plane is transformed by the inverse of the modelview matrix at this call.
  const Vec4 p(equation[0], equation[1], equation[2], equation[3]);
  transform_.clip_plane[plane - GL_CLIP_PLANE0] = p * glm::inverse(transform_.modelview.back());
}

const Mat4& Context::normal_matrix() {
  if (normal_matrix_dirty_) {
    normal_matrix_ = glm::inverse(transform_.modelview.back());
    normal_matrix_dirty_ = false;
  }
  return normal_matrix_;
}

}  // namespace passim
