// Context: coordinate transformation (§2.10), vertices and primitives (§2.6-2.8),
// lighting state (§2.13), and the rasterization state of §3.3-3.5.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include <atomic>

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

// ---------------------------------------------------------------- current values (§2.7)

void Context::apply_color_material() {
  if (!lighting_.color_material) return;
  materials_dirty_ = true;
  const GLenum face = lighting_.color_material_face;
  for (int f = 0; f < 2; ++f) {
    if ((f == 0 && face == GL_BACK) || (f == 1 && face == GL_FRONT)) continue;
    Material& m = lighting_.material[f];
    switch (lighting_.color_material_mode) {
      case GL_EMISSION: m.emission = current_.color; break;
      case GL_AMBIENT: m.ambient = current_.color; break;
      case GL_DIFFUSE: m.diffuse = current_.color; break;
      case GL_SPECULAR: m.specular = current_.color; break;
      default: m.ambient = m.diffuse = current_.color; break;
    }
  }
}

#define PASSIM_SET_COLOR(r, g, b, a)            \
  current_.color = Vec4((r), (g), (b), (a));    \
  apply_color_material();

void Context::glColor3f(GLfloat r, GLfloat g, GLfloat b) { PASSIM_ENTRY(r, g, b) PASSIM_SET_COLOR(r, g, b, 1.0) }
void Context::glColor4f(GLfloat r, GLfloat g, GLfloat b, GLfloat a) { PASSIM_ENTRY(r, g, b, a) PASSIM_SET_COLOR(r, g, b, a) }
void Context::glColor3d(GLdouble r, GLdouble g, GLdouble b) { PASSIM_ENTRY(r, g, b) PASSIM_SET_COLOR(r, g, b, 1.0) }
void Context::glColor4d(GLdouble r, GLdouble g, GLdouble b, GLdouble a) { PASSIM_ENTRY(r, g, b, a) PASSIM_SET_COLOR(r, g, b, a) }
// Table 2.6: unsigned bytes map to c / 255.
void Context::glColor3ub(GLubyte r, GLubyte g, GLubyte b) {
  PASSIM_ENTRY(r, g, b)
  PASSIM_SET_COLOR(r / 255.0, g / 255.0, b / 255.0, 1.0)
}
void Context::glColor4ub(GLubyte r, GLubyte g, GLubyte b, GLubyte a) {
  PASSIM_ENTRY(r, g, b, a)
  PASSIM_SET_COLOR(r / 255.0, g / 255.0, b / 255.0, a / 255.0)
}
void Context::glColor3fv(const GLfloat* v) { PASSIM_ENTRY(v) PASSIM_SET_COLOR(v[0], v[1], v[2], 1.0) }
void Context::glColor3ubv(const GLubyte* v) {
  PASSIM_ENTRY(v)
  PASSIM_SET_COLOR(v[0] / 255.0, v[1] / 255.0, v[2] / 255.0, 1.0)
}
void Context::glColor4ubv(const GLubyte* v) {
  PASSIM_ENTRY(v)
  PASSIM_SET_COLOR(v[0] / 255.0, v[1] / 255.0, v[2] / 255.0, v[3] / 255.0)
}
void Context::glColor3dv(const GLdouble* v) { PASSIM_ENTRY(v) PASSIM_SET_COLOR(v[0], v[1], v[2], 1.0) }
void Context::glColor4dv(const GLdouble* v) { PASSIM_ENTRY(v) PASSIM_SET_COLOR(v[0], v[1], v[2], v[3]) }
void Context::glColor4fv(const GLfloat* v) { PASSIM_ENTRY(v) PASSIM_SET_COLOR(v[0], v[1], v[2], v[3]) }
#undef PASSIM_SET_COLOR

void Context::glNormal3f(GLfloat x, GLfloat y, GLfloat z) { PASSIM_ENTRY(x, y, z) current_.normal = Vec3(x, y, z); }
void Context::glNormal3d(GLdouble x, GLdouble y, GLdouble z) { PASSIM_ENTRY(x, y, z) current_.normal = Vec3(x, y, z); }
void Context::glNormal3fv(const GLfloat* v) { PASSIM_ENTRY(v) current_.normal = Vec3(v[0], v[1], v[2]); }
void Context::glNormal3dv(const GLdouble* v) { PASSIM_ENTRY(v) current_.normal = Vec3(v[0], v[1], v[2]); }

void Context::glTexCoord1f(GLfloat s) { PASSIM_ENTRY(s) current_.texcoord = Vec4(s, 0.0, 0.0, 1.0); }
void Context::glTexCoord2f(GLfloat s, GLfloat t) { PASSIM_ENTRY(s, t) current_.texcoord = Vec4(s, t, 0.0, 1.0); }
void Context::glTexCoord3f(GLfloat s, GLfloat t, GLfloat r) { PASSIM_ENTRY(s, t, r) current_.texcoord = Vec4(s, t, r, 1.0); }
void Context::glTexCoord4f(GLfloat s, GLfloat t, GLfloat r, GLfloat q) { PASSIM_ENTRY(s, t, r, q) current_.texcoord = Vec4(s, t, r, q); }
void Context::glTexCoord4d(GLdouble s, GLdouble t, GLdouble r, GLdouble q) { PASSIM_ENTRY(s, t, r, q) current_.texcoord = Vec4(s, t, r, q); }
void Context::glTexCoord2fv(const GLfloat* v) { PASSIM_ENTRY(v) current_.texcoord = Vec4(v[0], v[1], 0.0, 1.0); }
void Context::glTexCoord3fv(const GLfloat* v) { PASSIM_ENTRY(v) current_.texcoord = Vec4(v[0], v[1], v[2], 1.0); }
void Context::glTexCoord4fv(const GLfloat* v) { PASSIM_ENTRY(v) current_.texcoord = Vec4(v[0], v[1], v[2], v[3]); }
void Context::glTexCoord2d(GLdouble s, GLdouble t) { PASSIM_ENTRY(s, t) current_.texcoord = Vec4(s, t, 0.0, 1.0); }
void Context::glTexCoord2i(GLint s, GLint t) { PASSIM_ENTRY(s, t) current_.texcoord = Vec4(s, t, 0.0, 1.0); }
void Context::glTexCoord2dv(const GLdouble* v) { PASSIM_ENTRY(v) current_.texcoord = Vec4(v[0], v[1], 0.0, 1.0); }

// ---------------------------------------------------------------- vertices and primitives

void Context::glVertex2f(GLfloat x, GLfloat y) { PASSIM_ENTRY(x, y) submit_vertex(Vec4(x, y, 0.0, 1.0)); }
void Context::glVertex3f(GLfloat x, GLfloat y, GLfloat z) { PASSIM_ENTRY(x, y, z) submit_vertex(Vec4(x, y, z, 1.0)); }
void Context::glVertex4f(GLfloat x, GLfloat y, GLfloat z, GLfloat w) { PASSIM_ENTRY(x, y, z, w) submit_vertex(Vec4(x, y, z, w)); }
void Context::glVertex2d(GLdouble x, GLdouble y) { PASSIM_ENTRY(x, y) submit_vertex(Vec4(x, y, 0.0, 1.0)); }
void Context::glVertex3d(GLdouble x, GLdouble y, GLdouble z) { PASSIM_ENTRY(x, y, z) submit_vertex(Vec4(x, y, z, 1.0)); }
void Context::glVertex4d(GLdouble x, GLdouble y, GLdouble z, GLdouble w) { PASSIM_ENTRY(x, y, z, w) submit_vertex(Vec4(x, y, z, w)); }
void Context::glVertex2dv(const GLdouble* v) { PASSIM_ENTRY(v) submit_vertex(Vec4(v[0], v[1], 0.0, 1.0)); }
void Context::glVertex3dv(const GLdouble* v) { PASSIM_ENTRY(v) submit_vertex(Vec4(v[0], v[1], v[2], 1.0)); }
void Context::glVertex2iv(const GLint* v) { PASSIM_ENTRY(v) submit_vertex(Vec4(v[0], v[1], 0.0, 1.0)); }
void Context::glVertex3iv(const GLint* v) { PASSIM_ENTRY(v) submit_vertex(Vec4(v[0], v[1], v[2], 1.0)); }
void Context::glVertex2i(GLint x, GLint y) { PASSIM_ENTRY(x, y) submit_vertex(Vec4(x, y, 0.0, 1.0)); }
void Context::glVertex3i(GLint x, GLint y, GLint z) { PASSIM_ENTRY(x, y, z) submit_vertex(Vec4(x, y, z, 1.0)); }

void Context::glRectd(GLdouble x1, GLdouble y1, GLdouble x2, GLdouble y2) {
  PASSIM_ENTRY(x1, y1, x2, y2)
  glBegin(GL_POLYGON);
  glVertex2d(x1, y1);
  glVertex2d(x2, y1);
  glVertex2d(x2, y2);
  glVertex2d(x1, y2);
  glEnd();
}
// Float and integer coordinates are exact as doubles.
void Context::glRectf(GLfloat x1, GLfloat y1, GLfloat x2, GLfloat y2) { PASSIM_ENTRY(x1, y1, x2, y2) glRectd(x1, y1, x2, y2); }
void Context::glRecti(GLint x1, GLint y1, GLint x2, GLint y2) { PASSIM_ENTRY(x1, y1, x2, y2) glRectd(x1, y1, x2, y2); }

void Context::glVertex2fv(const GLfloat* v) { PASSIM_ENTRY(v) submit_vertex(Vec4(v[0], v[1], 0.0, 1.0)); }
void Context::glVertex3fv(const GLfloat* v) { PASSIM_ENTRY(v) submit_vertex(Vec4(v[0], v[1], v[2], 1.0)); }
void Context::glVertex4fv(const GLfloat* v) { PASSIM_ENTRY(v) submit_vertex(Vec4(v[0], v[1], v[2], v[3])); }

namespace {
bool is_primitive_mode(GLenum mode) { return mode <= GL_POLYGON; }
}  // namespace

void Context::glBegin(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (!is_primitive_mode(mode)) return set_error(GL_INVALID_ENUM);
  in_begin_ = true;
  begin_mode_ = mode;
  vertex_materials_.clear();
  materials_dirty_ = true;
  prim_vertices_.clear();
  prim_vertex_count_ = 0;
}

void Context::glEnd() {
  PASSIM_ENTRY()
  if (!in_begin_) return set_error(GL_INVALID_OPERATION);
  if (begin_mode_ == GL_POLYGON && prim_vertices_.size() >= 3) {
    std::vector<const ProcessedVertex*> ptrs;
    for (const auto& v : prim_vertices_) ptrs.push_back(&v);
    draw_polygon(ptrs.data(), static_cast<int>(ptrs.size()), prim_vertices_.front());
  }
  in_begin_ = false;
  prim_vertices_.clear();
}

double Context::vertex_color(double c, int bits) const {
  // §2.13.6 clamp to [0, 1]; A4 rounds to the fragment width unless the profile says otherwise.
  if (profile_.arithmetic.quantise_vertex_colors) return quantise(c, bits);
  return clamp_nan_low(c, 0.0, 1.0);
}

void Context::submit_vertex(const Vec4& object) {
  if (!in_begin_) return;  // §2.6.3: Vertex outside Begin/End is undefined; it is ignored here
  Counters& c = counters();
  ++c.vertices;
  emit_primitive_vertex(process_vertex(object, c));
}

bool Context::sphere_map_texgen() const {
  // §2.10.4: SPHERE_MAP generates s or t from the eye-space normal.
  return texturing_enabled_ && ((textures_.gen[0].enabled && textures_.gen[0].mode == GL_SPHERE_MAP) ||
                                (textures_.gen[1].enabled && textures_.gen[1].mode == GL_SPHERE_MAP));
}

void Context::prepare_vertex_processing() {
  const bool sphere_map = sphere_map_texgen();
  if (lighting_.enabled || sphere_map) normal_matrix();  // computed when the modelview changed
  if (lighting_.enabled && (materials_dirty_ || vertex_materials_.empty())) {
    vertex_materials_.push_back(lighting_.material);
    materials_dirty_ = false;
  }
}

ProcessedVertex Context::process_vertex(const Vec4& object, Counters& c) {
  prepare_vertex_processing();
  count_vertex_processing(c, 1);
  return transform_vertex(object, current_.normal);
}

void Context::count_vertex_processing(Counters& c, std::uint64_t vertices) const {
  // The modelled machine lights every vertex (and both faces with two-sided lighting), and
  // evaluates each enabled texgen coordinate while a texture target is enabled; the counters
  // say so. (The simulator lights only the faces of polygons that survive culling, and a
  // display-list block's distinct vertices once: the same bits.)
  if (lighting_.enabled) c.lighting_evaluations += vertices * (lighting_.two_side ? 2 : 1);
  if (texturing_enabled_)
    for (const TexGenState& g : textures_.gen)
      if (g.enabled) c.texgen_evaluations += vertices;
}

ProcessedVertex Context::transform_vertex(const Vec4& object, const Vec3& normal) const {
  // §2.10-2.13: transformation, lighting inputs or colour, texture coordinates. The result
  // is assembled at the end from locals, with no call in between, so that the compiler drops
  // the default initialisers' stores (a 128-byte memset per vertex, a third of this
  // function's time when it was built in place).
  const Vec4 eye = transform_.modelview.back() * object;
  const Vec4 clip = transform_.projection.back() * eye;
  std::array<Vec4, 2> color{Vec4(0.0), Vec4(0.0)};
  std::uint32_t material_index = 0;
  bool light_pending = false;
  const bool sphere_map = sphere_map_texgen();
  Vec3 n(0.0);
  if (lighting_.enabled || sphere_map) {
    // §2.10.3: normals transform by the inverse transpose of the modelview's upper 3x3.
    const Mat4& inv = normal_matrix_;  // fresh: prepare_vertex_processing
    n = Vec3(normal.x * inv[0][0] + normal.y * inv[0][1] + normal.z * inv[0][2],
             normal.x * inv[1][0] + normal.y * inv[1][1] + normal.z * inv[1][2],
             normal.x * inv[2][0] + normal.y * inv[2][1] + normal.z * inv[2][2]);
    if (transform_.normalize) {
      const double len = std::sqrt(glm::dot(n, n));
      if (len > 0.0) n /= len;
    } else if (transform_.rescale_normal) {
      const double f = 1.0 / std::sqrt(inv[0][2] * inv[0][2] + inv[1][2] * inv[1][2] + inv[2][2] * inv[2][2]);
      n *= f;
    }
  }
  if (lighting_.enabled) {
    // Lit when the polygon's facing is known (light_pending_vertex).
    material_index = static_cast<std::uint32_t>(vertex_materials_.size() - 1);
    light_pending = true;
  } else {
    for (int k = 0; k < 4; ++k) color[0][k] = vertex_color(current_.color[k], fragment_bits_[k]);
    color[1] = color[0];
  }
  // Texture coordinates are carried only while a texture target is enabled: texgen (§2.10.4),
  // then the texture matrix.
  Vec4 tex(0.0, 0.0, 0.0, 1.0);
  if (texturing_enabled_) {
    Vec4 tc = current_.texcoord;
    for (int k = 0; k < 4; ++k) {
      const TexGenState& g = textures_.gen[static_cast<std::size_t>(k)];
      if (!g.enabled) continue;
      if (g.mode == GL_OBJECT_LINEAR) {
        tc[k] = glm::dot(g.object_plane, object);
      } else if (g.mode == GL_EYE_LINEAR) {
        tc[k] = glm::dot(g.eye_plane, eye);
      } else {
        // SPHERE_MAP: u = unit eye->vertex, r = u − 2n'(n'·u), m = 2·sqrt(rx² + ry² + (rz + 1)²).
        Vec3 u = Vec3(eye) / eye.w;
        const double len = std::sqrt(glm::dot(u, u));
        if (len > 0.0) u /= len;
        const Vec3 r = u - 2.0 * n * glm::dot(n, u);
        const double m = 2.0 * std::sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
        tc[k] = (k == 0 ? r.x : r.y) / m + 0.5;
      }
    }
    tex = transform_.texture.back() * tc;
  }
  ProcessedVertex v;
  v.clip = clip;
  v.eye = eye;
  v.color = color;
  v.tex = tex;
  v.normal_eye = light_pending ? n : Vec3(0.0);
  v.material_index = material_index;
  v.light_pending = light_pending;
  return v;
}

void Context::light_pending_vertex(ProcessedVertex& v, int face) const {
  // §2.13.1 with the material current when the vertex was given; §2.13.6 clamp, A4 rounding.
  // No texturing between primary and secondary colour yet, so the colour sum happens here.
  const Material& m = vertex_materials_[v.material_index][static_cast<std::size_t>(face)];
  const LitColor lit = light_vertex(lighting_, m, v.eye, face == 0 ? v.normal_eye : -v.normal_eye);
  for (int k = 0; k < 4; ++k) {
    const double value = lit.primary[k] + (k < 3 ? lit.secondary[k] : 0.0);
    v.color[static_cast<std::size_t>(face)][k] = vertex_color(value, fragment_bits_[k]);
  }
  if (!lighting_.two_side) v.color[1] = v.color[0];
}

void Context::emit_primitive_vertex(const ProcessedVertex& v) {
  const std::uint64_t i = prim_vertex_count_++;
  auto& buf = prim_vertices_;
  switch (begin_mode_) {
    case GL_POINTS: draw_point(v); return;
    case GL_LINES: case GL_LINE_STRIP: case GL_LINE_LOOP:
      warn_once("line primitives are not rasterized yet: they produce no fragments");
      if (begin_mode_ == GL_LINES ? (i % 2 == 1) : i >= 1) ++counters().primitives_in;
      return;
    case GL_TRIANGLES: {
      buf.push_back(v);
      if (buf.size() == 3) {
        const ProcessedVertex* p[3] = {&buf[0], &buf[1], &buf[2]};
        draw_polygon(p, 3, buf[2]);
        buf.clear();
      }
      return;
    }
    case GL_TRIANGLE_STRIP: {
      buf.push_back(v);
      if (buf.size() == 3) {
        // §2.6.1: triangle i is (i, i+1, i+2), with the first two swapped for odd i
        // so that every triangle keeps the strip's orientation.
        const ProcessedVertex* p[3] = {&buf[0], &buf[1], &buf[2]};
        if (i % 2 == 1) std::swap(p[0], p[1]);
        draw_polygon(p, 3, buf[2]);
        buf.erase(buf.begin());
      }
      return;
    }
    case GL_TRIANGLE_FAN: {
      buf.push_back(v);
      if (buf.size() == 3) {
        const ProcessedVertex* p[3] = {&buf[0], &buf[1], &buf[2]};
        draw_polygon(p, 3, buf[2]);
        buf.erase(buf.begin() + 1);
      }
      return;
    }
    case GL_QUADS: {
      buf.push_back(v);
      if (buf.size() == 4) {
        if (profile_.arithmetic.immediate_quads_as_triangle_pairs && !drawing_arrays_) {
          // The profile's decomposition (profile.hpp); the provoking vertex stays v3.
          const ProcessedVertex* first[3] = {&buf[0], &buf[1], &buf[3]};
          const ProcessedVertex* second[3] = {&buf[1], &buf[2], &buf[3]};
          draw_polygon(first, 3, buf[3]);
          draw_polygon(second, 3, buf[3]);
        } else {
          const ProcessedVertex* p[4] = {&buf[0], &buf[1], &buf[2], &buf[3]};
          draw_polygon(p, 4, buf[3]);
        }
        buf.clear();
      }
      return;
    }
    case GL_QUAD_STRIP: {
      buf.push_back(v);
      if (buf.size() == 4) {
        // §2.6.1: quad j is (2j, 2j+1, 2j+3, 2j+2); the provoking vertex is 2j+3.
        const ProcessedVertex* p[4] = {&buf[0], &buf[1], &buf[3], &buf[2]};
        draw_polygon(p, 4, buf[3]);
        buf.erase(buf.begin(), buf.begin() + 2);
      }
      return;
    }
    default:  // GL_POLYGON: drawn at End
      buf.push_back(v);
      return;
  }
}

RasterVertex Context::to_window(const ProcessedVertex& v, int face) const {
  // §2.10.1: viewport transformation of normalised device coordinates.
  RasterVertex r;
  const double iw = 1.0 / v.clip.w;
  // A subnormal w (found by fuzzing) has an infinite reciprocal: divide instead, which keeps
  // x/w within [-1, 1] after clipping. Every other w keeps the reciprocal, and its bits.
  const bool tiny_w = !std::isfinite(iw);
  auto ndc = [&](double c) { return tiny_w ? c / v.clip.w : c * iw; };
  const double half_w = viewport_.width / 2.0, half_h = viewport_.height / 2.0;
  r.x = ndc(v.clip.x) * half_w + (viewport_.x + half_w);
  r.y = ndc(v.clip.y) * half_h + (viewport_.y + half_h);
  const double n = viewport_.near_val, f = viewport_.far_val;
  r.z = ndc(v.clip.z) * ((f - n) / 2.0) + (n + f) / 2.0;
  r.w = v.clip.w;
  r.color = v.color[face];
  r.tex = v.tex;
  r.eye_z = v.eye.z / v.eye.w;
  return r;
}

namespace {
ClipPlanes clip_planes_of(const TransformState& t) {
  ClipPlanes planes;
  planes.user = t.clip_plane;
  for (int k = 0; k < 6; ++k)
    if (t.clip_enabled[k]) planes.user_enabled |= 1u << k;
  return planes;
}
bool finite_vertex(const ProcessedVertex& v) {
  return std::isfinite(v.clip.x) && std::isfinite(v.clip.y) && std::isfinite(v.clip.z) && std::isfinite(v.clip.w) &&
         std::isfinite(v.eye.x) && std::isfinite(v.eye.y) && std::isfinite(v.eye.z) && std::isfinite(v.eye.w);
}
}  // namespace

void Context::draw_point(const ProcessedVertex& v) {
  Counters& c = counters();
  ++c.primitives_in;
  if (!finite_vertex(v)) {
    warn_once("a vertex with NaN or infinite coordinates was dropped (its primitive is counted as clipped out)");
    ++c.primitives_clipped_out;
    return;
  }
  if (!point_inside(v, clip_planes_of(transform_))) {
    ++c.primitives_clipped_out;
    return;
  }
  TriangleOptions options;
  const FragmentStagesSetup& setup = primitive_stages_setup(options);
  ProcessedVertex lit = v;
  if (lit.light_pending) light_pending_vertex(lit, 0);
  const RasterVertex w = to_window(lit, 0);
  if (!w.finite_position()) {
    warn_once("a vertex with NaN or infinite window coordinates was dropped (its primitive is counted as clipped out)");
    ++c.primitives_clipped_out;
    return;
  }
  if (scratch_->lanes) {
    scratch_->lanes->point(w, polygon_.point_size, setup, c);
    raster_queued_ = true;
    return;
  }
  rasterize_point(w, polygon_.point_size, setup.target, scratch_->spans, fragment_sink(), c);
}

bool Context::assemble_polygon(const ProcessedVertex* const* vertices, int count, const ProcessedVertex& provoking,
                               PolygonWork& work, Counters& c) const {
  ++c.primitives_in;
  std::vector<ProcessedVertex>& poly = work.polygon;
  poly.clear();
  for (int k = 0; k < count; ++k) {
    if (!finite_vertex(*vertices[k])) {
      work.warnings |= PolygonWork::kNonFiniteVertex;
      ++c.primitives_clipped_out;
      return false;
    }
    poly.push_back(*vertices[k]);
  }
  bool cut = false;
  if (!clip_polygon(poly, work.clip_scratch, clip_planes_of(transform_), cut)) {
    ++c.primitives_clipped_out;
    return false;
  }
  if (cut) ++c.primitives_clipped;

  // Window coordinates, then facing from the signed area (§3.5.1, eq. 3.6).
  std::vector<RasterVertex>& win = work.window;
  win.resize(poly.size());
  for (std::size_t k = 0; k < poly.size(); ++k) {
    win[k] = to_window(poly[k], 0);
    if (!win[k].finite_position()) {
      work.warnings |= PolygonWork::kNonFiniteWindow;
      ++c.primitives_clipped_out;
      return false;
    }
  }
  const Facing facing = polygon_facing(win.data(), win.size(), c);
  if (!facing.drawn) return false;
  const int face = facing.face;
  ProcessedVertex flat_source = provoking;
  if (provoking.light_pending) {
    // Light the polygon's vertices for the face that is drawn, then clip again with the lit
    // colours (the same clip, so the same positions; trivially inside polygons skip it).
    if (cut) {
      poly.clear();
      for (int k = 0; k < count; ++k) {
        poly.push_back(*vertices[k]);
        light_pending_vertex(poly.back(), face);
      }
      clip_polygon(poly, work.clip_scratch, clip_planes_of(transform_), cut);
    } else {
      for (ProcessedVertex& v : poly) light_pending_vertex(v, face);  // poly holds the vertices themselves
    }
    light_pending_vertex(flat_source, face);
    for (std::size_t k = 0; k < poly.size(); ++k) win[k].color = poly[k].color[static_cast<std::size_t>(face)];
  } else if (face == 1) {
    for (std::size_t k = 0; k < poly.size(); ++k) win[k].color = poly[k].color[1];
  }
  work.mode = facing.front ? polygon_.mode_front : polygon_.mode_back;
  work.flat_color = flat_source.color[static_cast<std::size_t>(face)];
  return true;
}

Context::Facing Context::polygon_facing(const RasterVertex* win, std::size_t count, Counters& c) const {
  double area = 0.0;
  for (std::size_t k = 0; k < count; ++k) {
    const RasterVertex& a = win[k];
    const RasterVertex& b = win[(k + 1) % count];
    area += a.x * b.y - b.x * a.y;
  }
  return facing_of_area(area, c);
}

Context::Facing Context::triangle_facing(const RasterVertex& a, const RasterVertex& b, const RasterVertex& v,
                                         Counters& c) const {
  double area = 0.0;
  area += a.x * b.y - b.x * a.y;
  area += b.x * v.y - v.x * b.y;
  area += v.x * a.y - a.x * v.y;
  return facing_of_area(area, c);
}

Context::Facing Context::facing_of_area(double area, Counters& c) const {
  Facing f;
  f.front = (polygon_.front_face == GL_CCW) ? area > 0.0 : area < 0.0;
  if (polygon_.cull_enabled && (polygon_.cull_face == GL_FRONT_AND_BACK ||
                                (f.front ? polygon_.cull_face == GL_FRONT : polygon_.cull_face == GL_BACK))) {
    ++c.primitives_culled;
    return f;
  }
  f.drawn = true;
  f.face = (lighting_.enabled && lighting_.two_side && !f.front) ? 1 : 0;
  return f;
}

void Context::note_polygon_warnings(unsigned warnings) {
  if (warnings & PolygonWork::kNonFiniteVertex)
    warn_once("a vertex with NaN or infinite coordinates was dropped (its primitive is counted as clipped out)");
  if (warnings & PolygonWork::kNonFiniteWindow)
    warn_once("a vertex with NaN or infinite window coordinates was dropped (its primitive is counted as clipped out)");
}

TriangleOptions Context::polygon_options(const TriangleOptions& setup_options, const Vec4& flat_color) const {
  TriangleOptions options = setup_options;
  options.flat = lighting_.shade_model == GL_FLAT;
  options.flat_color = flat_color;
  options.offset = polygon_.offset_fill;
  options.offset_factor = polygon_.offset_factor;
  options.offset_units = polygon_.offset_units;
  return options;
}

void Context::draw_polygon(const ProcessedVertex* const* vertices, int count, const ProcessedVertex& provoking) {
  Counters& c = counters();
  PolygonWork& work = scratch_->polygon_work;
  work.warnings = 0;
  const bool drawn = assemble_polygon(vertices, count, provoking, work, c);
  note_polygon_warnings(work.warnings);
  if (!drawn) return;
  const std::vector<RasterVertex>& win = work.window;
  TriangleOptions setup_options;
  const FragmentStagesSetup& setup = primitive_stages_setup(setup_options);
  RasterLanes* lanes = scratch_->lanes.get();
  if (lanes) raster_queued_ = true;
  if (work.mode == GL_POINT) {
    for (const RasterVertex& w : win) {
      if (lanes) lanes->point(w, polygon_.point_size, setup, c);
      else rasterize_point(w, polygon_.point_size, setup.target, scratch_->spans, fragment_sink(), c);
    }
    return;
  }
  if (work.mode == GL_LINE) {
    warn_once("glPolygonMode(GL_LINE) is not rasterized yet: such polygons produce no fragments");
    return;
  }
  const TriangleOptions options = polygon_options(setup_options, work.flat_color);
  // §3.5.1: a convex polygon may be decomposed; a fan from the first vertex.
  for (std::size_t k = 1; k + 1 < win.size(); ++k) {
    if (lanes) lanes->triangle(win[0], win[k], win[k + 1], options, setup, c);
    else rasterize_triangle(win[0], win[k], win[k + 1], options, setup.target, scratch_->spans, fragment_sink(), c);
  }
}

void Context::draw_triangle_batch(const TriangleBatch& batch, const std::vector<Call>& calls) {
  // Its glBegin has run. The batch is drawn as its calls would draw it, one by one, unless
  // it began separate triangles with every polygon filled (points and lines are drawn by
  // draw_polygon alone).
  if (!in_begin_ || begin_mode_ != GL_TRIANGLES || !prim_vertices_.empty() || polygon_.mode_front != GL_FILL ||
      polygon_.mode_back != GL_FILL) {
    for (std::size_t k = batch.begin_call + 1; k < batch.end_call; ++k) calls[k].info->invoke(*this, calls[k].args);
    return;
  }
  Counters& pass = counters();
  // The tasks below run on every lane that takes part, or on this thread alone.
  RasterLanes* lanes = scratch_->lanes.get();
  const auto run_task = [&](const std::function<void(int)>& task) { lanes ? lanes->run_task(task) : task(0); };
  prepare_vertex_processing();
  const Vec3 start_normal = current_.normal;
  const std::size_t count = batch.vertices.size(), triangles = count / 3;
  pass.vertices += 3 * triangles;
  count_vertex_processing(pass, 3 * triangles);
  // The distinct vertices, in chunks shared out among the lanes (ChunkClaims: each lane
  // starts on its own share, as it does with the triangles below, which then read mostly
  // vertices their own lane made): transformed, and those that can be drawn as they are (see
  // Scratch::BatchVertex) placed in the window and lit.
  const std::size_t distinct = batch.positions.size();
  std::vector<Scratch::BatchVertex>& vertices = scratch_->batch_vertices;
  if (vertices.size() < distinct) vertices.resize(distinct);
  const ClipPlanes planes = clip_planes_of(transform_);
  const int faces = lighting_.enabled && lighting_.two_side ? 2 : 1;
  const int lane_count = lanes ? lanes->lanes() : 1;
  constexpr std::size_t kChunkVertices = 64;
  ChunkClaims vertex_chunks((distinct + kChunkVertices - 1) / kChunkVertices, lane_count);
  run_task([&](int lane) {
    for (std::size_t chunk = vertex_chunks.next(lane); chunk < vertex_chunks.count(); chunk = vertex_chunks.next(lane)) {
      const std::size_t first = chunk * kChunkVertices;
      for (std::size_t i = first; i < std::min(distinct, first + kChunkVertices); ++i) {
        Scratch::BatchVertex& d = vertices[i];
        d.vertex = transform_vertex(batch.positions[i], batch.inherits[i] ? start_normal : batch.normals[i]);
        d.window = to_window(d.vertex, 0);
        d.simple = finite_vertex(d.vertex) && trivially_inside(d.vertex, planes) && d.window.finite_position();
        if (!d.simple || !d.vertex.light_pending) continue;
        for (int face = 0; face < faces; ++face) {
          ProcessedVertex lit = d.vertex;
          light_pending_vertex(lit, face);
          d.lit[static_cast<std::size_t>(face)] = lit.color[static_cast<std::size_t>(face)];
        }
      }
    }
  });
  // Chunks of triangles go to the lanes the same way (a worker still rasterizing what is
  // queued joins when it is free, or not at all; the task touches nothing rasterization
  // does: it reads state and writes its lane's counters and its chunks); each chunk is
  // assembled the same way by any lane, and the chunks are queued in order.
  constexpr std::size_t kChunkTriangles = 32;
  const std::size_t chunks = (triangles + kChunkTriangles - 1) / kChunkTriangles;
  std::vector<Scratch::BatchLane>& works = scratch_->batch_lanes;
  // The chunks' storage: the set the raster queue may still refer to is run first.
  const int set = scratch_->next_chunk_set;
  scratch_->next_chunk_set = 1 - set;
  if (lanes && lanes->pending() && scratch_->chunk_set_queue[set] == lanes->queue_serial()) lanes->flush(pass);
  std::vector<Scratch::BatchChunk>& drawn = scratch_->batch_chunks[set];
  works.resize(lanes ? static_cast<std::size_t>(lanes->lanes()) : 1);
  if (drawn.size() < chunks) drawn.resize(chunks);
  for (Scratch::BatchLane& share : works) {  // a lane that takes no part adds nothing
    share.counters = Counters{};
    share.first_warned[0] = share.first_warned[1] = SIZE_MAX;
  }
  ChunkClaims triangle_chunks(chunks, lane_count);
  run_task([&](int lane) {
    Scratch::BatchLane& share = works[static_cast<std::size_t>(lane)];
    PolygonWork& work = share.work;
    Counters& counted = share.counters;
    for (std::size_t chunk = triangle_chunks.next(lane); chunk < chunks; chunk = triangle_chunks.next(lane)) {
      std::vector<AssembledTriangle>& out = drawn[chunk].triangles;
      std::vector<TriangleRows>& out_rows = drawn[chunk].rows;
      out.clear();
      out_rows.clear();
      const std::size_t last = std::min(triangles, (chunk + 1) * kChunkTriangles);
      for (std::size_t t = chunk * kChunkTriangles; t < last; ++t) {
        const Scratch::BatchVertex* d[3] = {&vertices[batch.vertices[3 * t]], &vertices[batch.vertices[3 * t + 1]],
                                            &vertices[batch.vertices[3 * t + 2]]};
        if (d[0]->simple && d[1]->simple && d[2]->simple) {
          // What assemble_polygon does with a triangle that is not clipped, from the vertices'
          // window positions and colours found once.
          ++counted.primitives_in;
          const Facing facing = triangle_facing(d[0]->window, d[1]->window, d[2]->window, counted);
          if (!facing.drawn) continue;
          const auto face = static_cast<std::size_t>(facing.face);
          const bool lit = d[2]->vertex.light_pending;  // the provoking vertex
          // Made where it is kept (a triangle is 352 bytes: copying one made aside was a third
          // of the task's time).
          AssembledTriangle& drawn_triangle =
              out.emplace_back(d[0]->window, d[1]->window, d[2]->window,
                               lit ? d[2]->lit[face] : d[2]->vertex.color[face], t);
          for (int k = 0; k < 3; ++k)
            if (lit || face == 1) drawn_triangle.v[k].color = lit ? d[k]->lit[face] : d[k]->vertex.color[face];
          out_rows.push_back(triangle_rows(drawn_triangle.v[0], drawn_triangle.v[1], drawn_triangle.v[2],
                                           profile_.limits.subpixel_bits, fb_.config.height));
          continue;
        }
        const ProcessedVertex* p[3] = {&d[0]->vertex, &d[1]->vertex, &d[2]->vertex};
        work.warnings = 0;
        const bool drawn_here = assemble_polygon(p, 3, d[2]->vertex, work, counted);
        for (unsigned kind = 0; kind < 2; ++kind)
          if (work.warnings & (1u << kind)) share.first_warned[kind] = std::min(share.first_warned[kind], t);
        if (!drawn_here) continue;
        const std::vector<RasterVertex>& win = work.window;
        for (std::size_t k = 1; k + 1 < win.size(); ++k) {
          out.emplace_back(win[0], win[k], win[k + 1], work.flat_color, t);
          out_rows.push_back(triangle_rows(win[0], win[k], win[k + 1], profile_.limits.subpixel_bits, fb_.config.height));
        }
      }
    }
  });
  // The lanes' counters (sums); the warnings and the stage setup (which may warn too, and is
  // made at the first triangle drawn) in the order the calls one by one would meet them;
  // then the triangles to the raster queue in order.
  std::size_t first_warned[2] = {SIZE_MAX, SIZE_MAX}, first_drawn = SIZE_MAX;
  for (const Scratch::BatchLane& share : works) {
    pass += share.counters;
    for (int kind = 0; kind < 2; ++kind) first_warned[kind] = std::min(first_warned[kind], share.first_warned[kind]);
  }
  for (std::size_t chunk = 0; chunk < chunks && first_drawn == SIZE_MAX; ++chunk)
    if (!drawn[chunk].triangles.empty()) first_drawn = drawn[chunk].triangles.front().source;
  std::array<std::pair<std::size_t, int>, 3> events{
      {{first_warned[0], 0}, {first_warned[1], 1}, {first_drawn, 2}}};
  std::sort(events.begin(), events.end());
  TriangleOptions setup_options;
  const FragmentStagesSetup* setup = nullptr;
  for (const auto& [at, what] : events) {
    if (at == SIZE_MAX) break;
    if (what == 2) setup = &primitive_stages_setup(setup_options);
    else note_polygon_warnings(what == 0 ? PolygonWork::kNonFiniteVertex : PolygonWork::kNonFiniteWindow);
  }
  if (setup && lanes) {
    raster_queued_ = true;
    // By reference (each triangle's options are these but for its flat colour).
    const TriangleOptions options = polygon_options(setup_options, Vec4{});
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
      lanes->triangles(drawn[chunk].triangles.data(), drawn[chunk].rows.data(), drawn[chunk].triangles.size(), options,
                       *setup, pass);
    scratch_->chunk_set_queue[set] = lanes->queue_serial();
  } else if (setup) {
    TriangleOptions options = polygon_options(setup_options, Vec4{});
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
      for (std::size_t t = 0; t < drawn[chunk].triangles.size(); ++t) {
        const AssembledTriangle& triangle = drawn[chunk].triangles[t];
        options.flat_color = triangle.flat_color;
        rasterize_triangle(triangle.v[0], triangle.v[1], triangle.v[2], options, setup->target, scratch_->spans,
                           fragment_sink(), pass, &drawn[chunk].rows[t]);
      }
  }
  prim_vertex_count_ += 3 * triangles;
  // The vertices after the last whole triangle wait for the next, as their calls would leave them.
  for (std::size_t i = 3 * triangles; i < count; ++i) {
    const std::uint32_t v = batch.vertices[i];
    current_.normal = batch.inherits[v] ? start_normal : batch.normals[v];
    submit_vertex(batch.positions[v]);
  }
  if (batch.sets_normal) current_.normal = batch.last_normal;
}

// ---------------------------------------------------------------- vertex arrays (§2.8)

namespace {
ClientArray* array_of(ClientArrayState& s, GLenum a) {
  switch (a) {
    case GL_VERTEX_ARRAY: return &s.vertex;
    case GL_NORMAL_ARRAY: return &s.normal;
    case GL_COLOR_ARRAY: return &s.color;
    case GL_TEXTURE_COORD_ARRAY: return &s.texcoord;
    default: return nullptr;
  }
}
bool is_array_type(GLenum type, bool allow_unsigned, bool allow_byte) {
  switch (type) {
    case GL_SHORT: case GL_INT: case GL_FLOAT: case GL_DOUBLE: return true;
    case GL_BYTE: return allow_byte;
    case GL_UNSIGNED_BYTE: case GL_UNSIGNED_SHORT: case GL_UNSIGNED_INT: return allow_unsigned;
    default: return false;
  }
}
}  // namespace

void Context::glEnableClientState(GLenum array) {
  PASSIM_ENTRY(array)
  ClientArray* a = array_of(arrays_, array);
  if (!a) return set_error(GL_INVALID_ENUM);
  a->enabled = true;
}

void Context::glDisableClientState(GLenum array) {
  PASSIM_ENTRY(array)
  ClientArray* a = array_of(arrays_, array);
  if (!a) return set_error(GL_INVALID_ENUM);
  a->enabled = false;
}

#define PASSIM_SET_POINTER(member, size_, type_, stride_, ptr_) \
  arrays_.member.size = (size_);                                 \
  arrays_.member.type = (type_);                                 \
  arrays_.member.stride = (stride_);                             \
  arrays_.member.pointer = (ptr_);                               \
  arrays_.member.extent = SIZE_MAX;

void Context::glVertexPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (size < 2 || size > 4 || stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, false, false)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(vertex, size, type, stride, pointer)
}

void Context::glNormalPointer(GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, false, true)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(normal, 3, type, stride, pointer)
}

void Context::glColorPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (size < 3 || size > 4 || stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, true, true)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(color, size, type, stride, pointer)
}

void Context::glTexCoordPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (size < 1 || size > 4 || stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, false, false)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(texcoord, size, type, stride, pointer)
}
#undef PASSIM_SET_POINTER

Vec4 Context::array_value_at(const ClientArray& a, int i, bool normalise) const {
  // Reads element i; with `normalise`, integer components map to [0,1] or [-1,1] (Table 2.6).
  const int ts = type_size(a.type);
  const std::size_t stride = a.stride ? static_cast<std::size_t>(a.stride) : static_cast<std::size_t>(ts * a.size);
  const std::byte* p = static_cast<const std::byte*>(a.pointer) + stride * static_cast<std::size_t>(i);
  Vec4 out(0.0, 0.0, 0.0, 1.0);
  for (int k = 0; k < a.size; ++k) {
    const std::byte* e = p + k * ts;
    double v = 0.0;
    switch (a.type) {
      case GL_FLOAT: { float f; std::memcpy(&f, e, 4); v = f; break; }
      case GL_DOUBLE: { std::memcpy(&v, e, 8); break; }
      case GL_INT: { std::int32_t x; std::memcpy(&x, e, 4); v = normalise ? (2.0 * x + 1.0) / 4294967295.0 : x; break; }
      case GL_UNSIGNED_INT: { std::uint32_t x; std::memcpy(&x, e, 4); v = normalise ? x / 4294967295.0 : x; break; }
      case GL_SHORT: { std::int16_t x; std::memcpy(&x, e, 2); v = normalise ? (2.0 * x + 1.0) / 65535.0 : x; break; }
      case GL_UNSIGNED_SHORT: { std::uint16_t x; std::memcpy(&x, e, 2); v = normalise ? x / 65535.0 : x; break; }
      case GL_BYTE: { std::int8_t x; std::memcpy(&x, e, 1); v = normalise ? (2.0 * x + 1.0) / 255.0 : x; break; }
      case GL_UNSIGNED_BYTE: { std::uint8_t x; std::memcpy(&x, e, 1); v = normalise ? x / 255.0 : x; break; }
      default: break;
    }
    out[k] = v;
  }
  return out;
}

void Context::check_array_bounds(std::int64_t max_index) const {
  auto check = [&](const ClientArray& a, const char* name) {
    if (!a.enabled) return;
    // An enabled array without a pointer: undefined in GL (a crash on real drivers).
    if (!a.pointer)
      throw ClientDataError(fmt::format("{} draws with the {} array enabled but no {} pointer given", current_call_,
                                        name, name));
    if (a.extent == SIZE_MAX) return;
    const CheckedSize elem = CheckedSize(type_size(a.type)) * a.size;
    const CheckedSize stride = a.stride ? CheckedSize(a.stride) : elem;
    bool inside = max_index >= 0 && max_index <= std::numeric_limits<int>::max();
    try {
      inside = inside && CheckedSize(max_index) * stride + elem <= CheckedSize(a.extent);
    } catch (const SizeOverflow&) {
      inside = false;
    }
    if (!inside)
      throw ClientDataError(fmt::format("{} reads element {} of the {} array, but only {} bytes were given",
                                        current_call_, max_index, name, a.extent));
  };
  check(arrays_.vertex, "vertex");
  check(arrays_.normal, "normal");
  check(arrays_.color, "color");
  check(arrays_.texcoord, "texture coordinate");
}

void Context::array_element_impl(int i) {
  // §2.8: ArrayElement is the sequence of Normal, Color, TexCoord and (last) Vertex calls.
  if (arrays_.normal.enabled) {
    Vec4 n = array_value_at(arrays_.normal, i, true);
    glNormal3d(n.x, n.y, n.z);
  }
  if (arrays_.color.enabled) {
    Vec4 c = array_value_at(arrays_.color, i, true);
    glColor4d(c.r, c.g, c.b, c.a);
  }
  if (arrays_.texcoord.enabled) {
    Vec4 t = array_value_at(arrays_.texcoord, i, false);
    glTexCoord4d(t.x, t.y, t.z, t.w);
  }
  if (arrays_.vertex.enabled) {
    Vec4 v = array_value_at(arrays_.vertex, i, false);
    glVertex4d(v.x, v.y, v.z, v.w);
  }
}

void Context::compile_array_element(int i, std::vector<Call>& out) const {
  auto add = [&](const char* name, Vec4 v, int n) {
    Call call{find_call(name), {}};
    call.args.reserve(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      Value x;
      x.d = v[k];
      call.args.push_back(x);
    }
    out.push_back(std::move(call));
  };
  check_array_bounds(i);
  if (arrays_.normal.enabled) add("glNormal3d", array_value_at(arrays_.normal, i, true), 3);
  if (arrays_.color.enabled) add("glColor4d", array_value_at(arrays_.color, i, true), 4);
  if (arrays_.texcoord.enabled) add("glTexCoord4d", array_value_at(arrays_.texcoord, i, false), 4);
  if (arrays_.vertex.enabled) add("glVertex4d", array_value_at(arrays_.vertex, i, false), 4);
}

void Context::record_client_arrays(int max_index) {
  // Emits glXxxPointer calls carrying the elements 0..max_index, tightly packed.
  check_array_bounds(max_index);
  auto emit = [&](const ClientArray& a, const char* name, bool has_size) {
    if (!a.enabled || !a.pointer) return;
    const int ts = type_size(a.type);
    const std::size_t elem = static_cast<std::size_t>(ts * a.size);
    const std::size_t stride = a.stride ? static_cast<std::size_t>(a.stride) : elem;
    std::vector<std::byte> packed(elem * static_cast<std::size_t>(max_index + 1));
    for (int k = 0; k <= max_index; ++k)
      std::memcpy(packed.data() + elem * k, static_cast<const std::byte*>(a.pointer) + stride * k, elem);
    Call call{find_call(name), {}};
    Value size, type, zero, data;
    size.i = a.size;
    type.i = a.type;
    data = detail::array_value(packed.data(), a.type, static_cast<std::size_t>(a.size) * (max_index + 1));
    if (has_size) call.args.push_back(size);
    call.args.push_back(type);
    call.args.push_back(zero);
    call.args.push_back(data);
    sink_->on_call(call);
  };
  emit(arrays_.vertex, "glVertexPointer", true);
  emit(arrays_.normal, "glNormalPointer", false);
  emit(arrays_.color, "glColorPointer", true);
  emit(arrays_.texcoord, "glTexCoordPointer", true);
}

void Context::glArrayElement(GLint i) {
  PASSIM_ENTRY(i)
  if (i < 0) return;
  check_array_bounds(i);
  array_element_impl(i);
}

namespace {
// Marks a glDrawArrays / glDrawElements for its duration, also when a trace error leaves it.
struct ArraysScope {
  bool& flag;
  explicit ArraysScope(bool& f) : flag(f) { flag = true; }
  ~ArraysScope() { flag = false; }
  ArraysScope(const ArraysScope&) = delete;
  ArraysScope& operator=(const ArraysScope&) = delete;
};
}  // namespace

void Context::glDrawArrays(GLenum mode, GLint first, GLsizei count) {
  PASSIM_ENTRY(mode, first, count)
  if (!is_primitive_mode(mode)) return set_error(GL_INVALID_ENUM);
  if (count < 0 || first < 0) return set_error(GL_INVALID_VALUE);
  if (count == 0) return;
  check_array_bounds(std::int64_t{first} + count - 1);
  const ArraysScope arrays(drawing_arrays_);
  glBegin(mode);
  for (GLint k = 0; k < count; ++k) array_element_impl(first + k);
  glEnd();
}

void Context::glDrawElements(GLenum mode, GLsizei count, GLenum type, const void* indices) {
  PASSIM_ENTRY(mode, count, type, indices)
  if (!is_primitive_mode(mode)) return set_error(GL_INVALID_ENUM);
  if (type != GL_UNSIGNED_BYTE && type != GL_UNSIGNED_SHORT && type != GL_UNSIGNED_INT)
    return set_error(GL_INVALID_ENUM);
  if (count < 0) return set_error(GL_INVALID_VALUE);
  if (count == 0 || !indices) return;
  std::vector<int> idx(static_cast<std::size_t>(count));
  std::int64_t max_index = 0;
  for (GLsizei k = 0; k < count; ++k) {
    std::uint32_t v;
    if (type == GL_UNSIGNED_BYTE) v = static_cast<const std::uint8_t*>(indices)[k];
    else if (type == GL_UNSIGNED_SHORT) v = static_cast<const std::uint16_t*>(indices)[k];
    else v = static_cast<const std::uint32_t*>(indices)[k];
    idx[static_cast<std::size_t>(k)] = static_cast<int>(v);  // ≤ INT_MAX once the bounds are checked
    max_index = std::max<std::int64_t>(max_index, v);
  }
  check_array_bounds(max_index);
  const ArraysScope arrays(drawing_arrays_);
  glBegin(mode);
  for (int i : idx) array_element_impl(i);
  glEnd();
}

// ---------------------------------------------------------------- lighting state (§2.13)

void Context::glShadeModel(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (mode != GL_FLAT && mode != GL_SMOOTH) return set_error(GL_INVALID_ENUM);
  lighting_.shade_model = mode;
}

void Context::set_light_param(GLenum light, GLenum pname, const double* v) {
  if (light < GL_LIGHT0 || light >= GL_LIGHT0 + lighting_.lights.size()) return set_error(GL_INVALID_ENUM);
  Light& L = lighting_.lights[light - GL_LIGHT0];
  switch (pname) {
    case GL_AMBIENT: L.ambient = Vec4(v[0], v[1], v[2], v[3]); break;
    case GL_DIFFUSE: L.diffuse = Vec4(v[0], v[1], v[2], v[3]); break;
    case GL_SPECULAR: L.specular = Vec4(v[0], v[1], v[2], v[3]); break;
    // §2.13.2: position and direction are transformed by the modelview matrix now.
    case GL_POSITION: L.position = transform_.modelview.back() * Vec4(v[0], v[1], v[2], v[3]); break;
    case GL_SPOT_DIRECTION: L.spot_direction = glm::dmat3(transform_.modelview.back()) * Vec3(v[0], v[1], v[2]); break;
    case GL_SPOT_EXPONENT:
      if (v[0] < 0.0 || v[0] > 128.0) return set_error(GL_INVALID_VALUE);
      L.spot_exponent = v[0];
      break;
    case GL_SPOT_CUTOFF:
      if ((v[0] < 0.0 || v[0] > 90.0) && v[0] != 180.0) return set_error(GL_INVALID_VALUE);
      L.spot_cutoff = v[0];
      break;
    case GL_CONSTANT_ATTENUATION:
    case GL_LINEAR_ATTENUATION:
    case GL_QUADRATIC_ATTENUATION:
      if (v[0] < 0.0) return set_error(GL_INVALID_VALUE);
      (pname == GL_CONSTANT_ATTENUATION ? L.constant_attenuation
       : pname == GL_LINEAR_ATTENUATION ? L.linear_attenuation
                                        : L.quadratic_attenuation) = v[0];
      break;
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glLightf(GLenum light, GLenum pname, GLfloat param) {
  PASSIM_ENTRY(light, pname, param)
  if (pname_count(pname) != 1) return set_error(GL_INVALID_ENUM);
  const double v = param;
  set_light_param(light, pname, &v);
}

void Context::glLighti(GLenum light, GLenum pname, GLint param) {
  PASSIM_ENTRY(light, pname, param)
  if (pname_count(pname) != 1) return set_error(GL_INVALID_ENUM);
  const double v = param;
  set_light_param(light, pname, &v);
}

void Context::glLightfv(GLenum light, GLenum pname, const GLfloat* params) {
  const int n = pname_count(pname);
  PASSIM_ENTRY(light, pname, params)
  if (n == 0) return set_error(GL_INVALID_ENUM);
  vector_parameter(params, n, [&](const double* v) { set_light_param(light, pname, v); });
}

void Context::set_light_model_param(GLenum pname, const double* v) {
  switch (pname) {
    case GL_LIGHT_MODEL_AMBIENT: lighting_.model_ambient = Vec4(v[0], v[1], v[2], v[3]); break;
    case GL_LIGHT_MODEL_LOCAL_VIEWER: lighting_.local_viewer = v[0] != 0.0; break;
    case GL_LIGHT_MODEL_TWO_SIDE: lighting_.two_side = v[0] != 0.0; break;
    case GL_LIGHT_MODEL_COLOR_CONTROL: {
      const GLenum c = enum_param(v[0]);
      if (c != GL_SINGLE_COLOR && c != GL_SEPARATE_SPECULAR_COLOR) return set_error(GL_INVALID_ENUM);
      lighting_.color_control = c;
      break;
    }
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glLightModelf(GLenum pname, GLfloat param) {
  PASSIM_ENTRY(pname, param)
  if (pname == GL_LIGHT_MODEL_AMBIENT) return set_error(GL_INVALID_ENUM);
  const double v = param;
  set_light_model_param(pname, &v);
}

void Context::glLightModeli(GLenum pname, GLint param) {
  PASSIM_ENTRY(pname, param)
  if (pname == GL_LIGHT_MODEL_AMBIENT) return set_error(GL_INVALID_ENUM);
  const double v = param;
  set_light_model_param(pname, &v);
}

void Context::glLightModelfv(GLenum pname, const GLfloat* params) {
  const int n = pname_count(pname);
  PASSIM_ENTRY(pname, params)
  if (n == 0) return set_error(GL_INVALID_ENUM);
  vector_parameter(params, n, [&](const double* v) { set_light_model_param(pname, v); });
}

void Context::set_material_param(GLenum face, GLenum pname, const double* v) {
  materials_dirty_ = true;
  if (face != GL_FRONT && face != GL_BACK && face != GL_FRONT_AND_BACK) return set_error(GL_INVALID_ENUM);
  if (pname == GL_SHININESS && (v[0] < 0.0 || v[0] > 128.0)) return set_error(GL_INVALID_VALUE);
  for (int f = 0; f < 2; ++f) {
    if ((f == 0 && face == GL_BACK) || (f == 1 && face == GL_FRONT)) continue;
    Material& m = lighting_.material[f];
    const Vec4 c(v[0], v[1], v[2], v[3]);
    switch (pname) {
      case GL_AMBIENT: m.ambient = c; break;
      case GL_DIFFUSE: m.diffuse = c; break;
      case GL_SPECULAR: m.specular = c; break;
      case GL_EMISSION: m.emission = c; break;
      case GL_AMBIENT_AND_DIFFUSE: m.ambient = m.diffuse = c; break;
      case GL_SHININESS: m.shininess = v[0]; break;
      case GL_COLOR_INDEXES: break;  // colour-index lighting: not modelled (RGBA only)
      default: return set_error(GL_INVALID_ENUM);
    }
  }
}

void Context::glMaterialf(GLenum face, GLenum pname, GLfloat param) {
  PASSIM_ENTRY(face, pname, param)
  if (pname != GL_SHININESS) return set_error(GL_INVALID_ENUM);
  const double v[4] = {param, 0, 0, 0};
  set_material_param(face, pname, v);
}

void Context::glMaterialfv(GLenum face, GLenum pname, const GLfloat* params) {
  const int n = pname_count(pname);
  PASSIM_ENTRY(face, pname, params)
  if (n == 0 || pname == GL_SPOT_DIRECTION) return set_error(GL_INVALID_ENUM);
  vector_parameter(params, n, [&](const double* v) { set_material_param(face, pname, v); });
}

void Context::glColorMaterial(GLenum face, GLenum mode) {
  PASSIM_ENTRY(face, mode)
  if (face != GL_FRONT && face != GL_BACK && face != GL_FRONT_AND_BACK) return set_error(GL_INVALID_ENUM);
  if (mode != GL_EMISSION && mode != GL_AMBIENT && mode != GL_DIFFUSE && mode != GL_SPECULAR &&
      mode != GL_AMBIENT_AND_DIFFUSE)
    return set_error(GL_INVALID_ENUM);
  lighting_.color_material_face = face;
  lighting_.color_material_mode = mode;
  apply_color_material();
}

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

}  // namespace passim
