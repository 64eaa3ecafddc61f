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

namespace {
// §2.7: a vertex or texture coordinate set of n components, the rest from (0, 0, 0, 1);
// integers are converted directly.
template <class T>
Vec4 coordinates(const T* v, int n) {
  Vec4 out(0.0, 0.0, 0.0, 1.0);
  for (int k = 0; k < n; ++k) out[k] = static_cast<double>(v[k]);
  return out;
}
// §2.7: colour and normal components by Table 2.6; a three-component colour has alpha 1.
template <class T>
Vec4 normalized(const T* v, int n) {
  Vec4 out(0.0, 0.0, 0.0, 1.0);
  for (int k = 0; k < n; ++k) out[k] = normalized_component(v[k]);
  return out;
}
}  // namespace

// The members of the families (context.hpp): the scalar form gathers its components into v,
// and both forms then do `apply`, which reads v's n components.
#define PASSIM_DEFINE_SCALAR(name, n, suffix, T, apply)                 \
  void Context::name##n##suffix(PASSIM_COMPONENT_PARAMS_##n(T)) {        \
    PASSIM_ENTRY(PASSIM_COMPONENT_ARGS_##n)                             \
    const T v[] = {PASSIM_COMPONENT_ARGS_##n};                          \
    apply;                                                              \
  }
#define PASSIM_DEFINE_VECTOR(name, n, suffix, T, apply) \
  void Context::name##n##suffix##v(const T* v) {        \
    PASSIM_ENTRY(v)                                     \
    apply;                                              \
  }
#define PASSIM_DEFINE_CALLS(name, n, suffix, T, apply) \
  PASSIM_DEFINE_SCALAR(name, n, suffix, T, apply) PASSIM_DEFINE_VECTOR(name, n, suffix, T, apply)

#define PASSIM_VERTEX(name, n, suffix, T, ...) PASSIM_DEFINE_CALLS(name, n, suffix, T, submit_vertex(coordinates(v, n)))
PASSIM_COORDINATE_TYPES(PASSIM_VERTEX, glVertex, 2)
PASSIM_COORDINATE_TYPES(PASSIM_VERTEX, glVertex, 3)
PASSIM_COORDINATE_TYPES(PASSIM_VERTEX, glVertex, 4)

#define PASSIM_TEX_COORD(name, n, suffix, T, ...) \
  PASSIM_DEFINE_CALLS(name, n, suffix, T, current_.texcoord = coordinates(v, n))
PASSIM_COORDINATE_TYPES(PASSIM_TEX_COORD, glTexCoord, 1)
PASSIM_COORDINATE_TYPES(PASSIM_TEX_COORD, glTexCoord, 2)
PASSIM_COORDINATE_TYPES(PASSIM_TEX_COORD, glTexCoord, 3)
PASSIM_COORDINATE_TYPES(PASSIM_TEX_COORD, glTexCoord, 4)

#define PASSIM_NORMAL(name, n, suffix, T, ...) \
  PASSIM_DEFINE_CALLS(name, n, suffix, T, current_.normal = Vec3(normalized(v, n)))
PASSIM_NORMAL_TYPES(PASSIM_NORMAL, glNormal, 3)

// §2.13.3: with COLOR_MATERIAL on, the new colour also sets the tracked material.
#define PASSIM_COLOR(name, n, suffix, T, ...) \
  PASSIM_DEFINE_CALLS(name, n, suffix, T, current_.color = normalized(v, n); apply_color_material())
PASSIM_COLOR_TYPES(PASSIM_COLOR, glColor, 3)
PASSIM_COLOR_TYPES(PASSIM_COLOR, glColor, 4)

// §2.12: RasterPos takes its coordinates as Vertex does. The position's rules and the family's
// first members are in context_pixels.cpp; the others are made here, beside Vertex's.
#define PASSIM_RASTER_POS(name, n, suffix, T, ...) set_raster_position(coordinates(v, n))
#define PASSIM_RASTER_POS_VECTOR(name, n, suffix, T, ...) \
  PASSIM_DEFINE_VECTOR(name, n, suffix, T, PASSIM_RASTER_POS(name, n, suffix, T))
#define PASSIM_RASTER_POS_SCALAR(name, n, suffix, T) \
  PASSIM_DEFINE_SCALAR(name, n, suffix, T, PASSIM_RASTER_POS(name, n, suffix, T))
PASSIM_COORDINATE_TYPES(PASSIM_RASTER_POS_VECTOR, glRasterPos, 2)
PASSIM_COORDINATE_TYPES(PASSIM_RASTER_POS_VECTOR, glRasterPos, 3)
PASSIM_COORDINATE_TYPES(PASSIM_RASTER_POS_VECTOR, glRasterPos, 4)
PASSIM_RASTER_POS_SCALAR(glRasterPos, 2, s, GLshort)
PASSIM_RASTER_POS_SCALAR(glRasterPos, 3, s, GLshort)
PASSIM_RASTER_POS_SCALAR(glRasterPos, 4, s, GLshort)
PASSIM_RASTER_POS_SCALAR(glRasterPos, 3, i, GLint)
PASSIM_RASTER_POS_SCALAR(glRasterPos, 4, i, GLint)
PASSIM_RASTER_POS_SCALAR(glRasterPos, 4, d, GLdouble)

// §2.6.2: the flag is stored; each vertex takes the current one (ProcessedVertex::edge_flag).
void Context::glEdgeFlag(GLboolean flag) { PASSIM_ENTRY(flag) current_.edge_flag = flag != GL_FALSE; }
void Context::glEdgeFlagv(const GLboolean* flag) { PASSIM_ENTRY(flag) current_.edge_flag = flag[0] != GL_FALSE; }

// §2.9: Rect(x1, y1, x2, y2) is Begin(POLYGON) Vertex2(x1, y1) Vertex2(x2, y1) Vertex2(x2, y2)
// Vertex2(x1, y2) End. Every type's coordinates are exact as doubles.
void Context::glRectd(GLdouble x1, GLdouble y1, GLdouble x2, GLdouble y2) {
  PASSIM_ENTRY(x1, y1, x2, y2)
  glBegin(GL_POLYGON);
  glVertex2d(x1, y1);
  glVertex2d(x2, y1);
  glVertex2d(x2, y2);
  glVertex2d(x1, y2);
  glEnd();
}
#define PASSIM_RECT_SCALAR(suffix, T) \
  void Context::glRect##suffix(T x1, T y1, T x2, T y2) { PASSIM_ENTRY(x1, y1, x2, y2) glRectd(x1, y1, x2, y2); }
PASSIM_RECT_SCALAR(s, GLshort)
PASSIM_RECT_SCALAR(i, GLint)
PASSIM_RECT_SCALAR(f, GLfloat)
#define PASSIM_RECT_VECTOR(name, n, suffix, T, ...) \
  void Context::name##suffix##v(const T* v1, const T* v2) { PASSIM_ENTRY(v1, v2) glRectd(v1[0], v1[1], v2[0], v2[1]); }
PASSIM_COORDINATE_TYPES(PASSIM_RECT_VECTOR, glRect, 2)

void Context::glBegin(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (!is_primitive_mode(mode)) return set_error(GL_INVALID_ENUM);
  in_begin_ = true;
  begin_mode_ = mode;
  vertex_materials_.clear();
  materials_dirty_ = true;
  prim_vertices_.clear();
  prim_vertex_count_ = 0;
  line_stipple_counter_ = 0;  // §3.4.2: reset whenever a Begin occurs
}

void Context::glEnd() {
  PASSIM_ENTRY()
  if (!in_begin_) return set_error(GL_INVALID_OPERATION);
  if (begin_mode_ == GL_POLYGON && prim_vertices_.size() >= 3) {
    std::vector<const ProcessedVertex*> ptrs;
    for (const auto& v : prim_vertices_) ptrs.push_back(&v);
    draw_polygon(ptrs.data(), static_cast<int>(ptrs.size()), prim_vertices_.front());
  }
  if (begin_mode_ == GL_LINE_LOOP && prim_vertices_.size() == 2) draw_line(prim_vertices_[1], prim_vertices_[0]);  // §2.6.1: the closing segment
  in_begin_ = false;
  prim_vertices_.clear();
}

}  // namespace passim
