// Context: vertices (§2.6-2.9): the current values, Begin/End, the immediate-mode variants
// and rectangles.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_internal.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/clipping.hpp"
#include "stages/lighting.hpp"
#include "stages/rasterizer.hpp"

namespace passim {

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

}  // namespace passim
