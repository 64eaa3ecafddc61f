// Context: lighting state (§2.13): lights, the light model, materials, colour material and
// the shading model.
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

}  // namespace passim
