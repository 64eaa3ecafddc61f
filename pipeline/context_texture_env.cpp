// Context: the texture environment (§3.8.9), texture coordinate generation (§2.10.4) and
// fog (§3.10).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "client/glu_mipmaps.hpp"
#include "client/pixel_pack.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/kernel_paths.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

// ---------------------------------------------------------------- environment (§3.8.9)

void Context::set_tex_env(GLenum target, GLenum pname, const double* v) {
  if (target != GL_TEXTURE_ENV) return set_error(GL_INVALID_ENUM);
  if (pname == GL_TEXTURE_ENV_MODE) {
    const GLenum m = enum_param(v[0]);
    if (m != GL_MODULATE && m != GL_DECAL && m != GL_BLEND && m != GL_REPLACE && m != GL_ADD)
      return set_error(GL_INVALID_ENUM);
    textures_.env_mode = m;
  } else if (pname == GL_TEXTURE_ENV_COLOR) {
    textures_.env_color = Vec4(clamp_nan_low(v[0], 0, 1), clamp_nan_low(v[1], 0, 1), clamp_nan_low(v[2], 0, 1),
                               clamp_nan_low(v[3], 0, 1));
  } else {
    set_error(GL_INVALID_ENUM);
  }
}

void Context::glTexEnvi(GLenum target, GLenum pname, GLint param) {
  PASSIM_ENTRY(target, pname, param)
  scalar_parameter(pname == GL_TEXTURE_ENV_COLOR, param, [&](const double* v) { set_tex_env(target, pname, v); });
}

void Context::glTexEnvf(GLenum target, GLenum pname, GLfloat param) {
  PASSIM_ENTRY(target, pname, param)
  scalar_parameter(pname == GL_TEXTURE_ENV_COLOR, param, [&](const double* v) { set_tex_env(target, pname, v); });
}

void Context::glTexEnvfv(GLenum target, GLenum pname, const GLfloat* params) {
  const int n = pname == GL_TEXTURE_ENV_COLOR ? 4 : 1;
  PASSIM_ENTRY(target, pname, params)
  vector_parameter(params, n, [&](const double* v) { set_tex_env(target, pname, v); });
}
// ---------------------------------------------------------------- coordinate generation (§2.10.4)

void Context::set_tex_gen(GLenum coord, GLenum pname, const double* v) {
  if (coord < GL_S || coord > GL_Q) return set_error(GL_INVALID_ENUM);
  TexGenState& g = textures_.gen[coord - GL_S];
  switch (pname) {
    case GL_TEXTURE_GEN_MODE: {
      const GLenum m = enum_param(v[0]);
      if (m != GL_OBJECT_LINEAR && m != GL_EYE_LINEAR && m != GL_SPHERE_MAP) return set_error(GL_INVALID_ENUM);
      if (m == GL_SPHERE_MAP && (coord == GL_R || coord == GL_Q)) return set_error(GL_INVALID_ENUM);
      g.mode = m;
      break;
    }
    case GL_OBJECT_PLANE: g.object_plane = Vec4(v[0], v[1], v[2], v[3]); break;
    case GL_EYE_PLANE:
      // The plane is transformed by the inverse modelview at this call: p' = p·M⁻¹.
      g.eye_plane = Vec4(v[0], v[1], v[2], v[3]) * glm::inverse(transform_.modelview.back());
      break;
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glTexGeni(GLenum coord, GLenum pname, GLint param) {
  PASSIM_ENTRY(coord, pname, param)
  scalar_parameter(pname != GL_TEXTURE_GEN_MODE, param, [&](const double* v) { set_tex_gen(coord, pname, v); });
}

void Context::glTexGenf(GLenum coord, GLenum pname, GLfloat param) {
  PASSIM_ENTRY(coord, pname, param)
  scalar_parameter(pname != GL_TEXTURE_GEN_MODE, param, [&](const double* v) { set_tex_gen(coord, pname, v); });
}

void Context::glTexGenfv(GLenum coord, GLenum pname, const GLfloat* params) {
  const int n = pname == GL_TEXTURE_GEN_MODE ? 1 : 4;
  PASSIM_ENTRY(coord, pname, params)
  vector_parameter(params, n, [&](const double* v) { set_tex_gen(coord, pname, v); });
}

void Context::glTexGendv(GLenum coord, GLenum pname, const GLdouble* params) {
  const int n = pname == GL_TEXTURE_GEN_MODE ? 1 : 4;
  PASSIM_ENTRY(coord, pname, params)
  vector_parameter(params, n, [&](const double* v) { set_tex_gen(coord, pname, v); });
}
// ---------------------------------------------------------------- fog (§3.10)

void Context::set_fog(GLenum pname, const double* v) {
  switch (pname) {
    case GL_FOG_MODE: {
      const GLenum m = enum_param(v[0]);
      if (m != GL_LINEAR && m != GL_EXP && m != GL_EXP2) return set_error(GL_INVALID_ENUM);
      fog_.mode = m;
      break;
    }
    case GL_FOG_DENSITY:
      if (v[0] < 0.0) return set_error(GL_INVALID_VALUE);
      fog_.density = v[0];
      break;
    case GL_FOG_START: fog_.start = v[0]; break;
    case GL_FOG_END: fog_.end = v[0]; break;
    case GL_FOG_COLOR:
      fog_.color = Vec4(clamp_nan_low(v[0], 0, 1), clamp_nan_low(v[1], 0, 1), clamp_nan_low(v[2], 0, 1),
                        clamp_nan_low(v[3], 0, 1));
      break;
    case GL_FOG_INDEX: break;  // colour-index mode: not modelled
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glFogf(GLenum pname, GLfloat param) {
  PASSIM_ENTRY(pname, param)
  scalar_parameter(pname == GL_FOG_COLOR, param, [&](const double* v) { set_fog(pname, v); });
}

void Context::glFogi(GLenum pname, GLint param) {
  PASSIM_ENTRY(pname, param)
  scalar_parameter(pname == GL_FOG_COLOR, param, [&](const double* v) { set_fog(pname, v); });
}

void Context::glFogfv(GLenum pname, const GLfloat* params) {
  const int n = pname == GL_FOG_COLOR ? 4 : 1;
  PASSIM_ENTRY(pname, params)
  vector_parameter(params, n, [&](const double* v) { set_fog(pname, v); });
}

}  // namespace passim
