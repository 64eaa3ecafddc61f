// Context: errors (§2.5), enables and disables (§2.11; the flags of chapter 6's tables) and
// the state queries (§6.1).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <mutex>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/accumulate.hpp"
#include "stages/clear.hpp"

namespace passim {

// ---------------------------------------------------------------- errors

namespace {
std::mutex& error_sites_mutex() {
  static std::mutex m;
  return m;
}
std::set<std::pair<std::string, int>>& error_sites() {
  static std::set<std::pair<std::string, int>> sites;
  return sites;
}
}  // namespace

void Context::set_error(GLenum error, const char* site_file, int site_line) {
  // §2.5: the first error is kept until glGetError reads it; every error is logged.
  if (error_ == GL_NO_ERROR) error_ = error;
  error_log_.push_back(GlErrorRecord{current_call_, error, where_});
  const std::string_view file = site_file;
  const std::size_t slash = file.find_last_of('/');
  std::lock_guard<std::mutex> lock(error_sites_mutex());
  error_sites().emplace(std::string(slash == std::string_view::npos ? file : file.substr(slash + 1)), site_line);
}

std::set<std::pair<std::string, int>> Context::error_sites_reached() {
  std::lock_guard<std::mutex> lock(error_sites_mutex());
  return error_sites();
}

void Context::forget_error_sites_reached() {
  std::lock_guard<std::mutex> lock(error_sites_mutex());
  error_sites().clear();
}

bool Context::rectangle_fits_in_memory(std::int64_t width, std::int64_t height) {
  if (width < 0 || height < 0) return true;  // INVALID_VALUE, raised by the call's own checks
  try {
    if ((CheckedSize(width) * height * kRectangleBytesPerPixel).value() <= memory_.left()) return true;
  } catch (const SizeOverflow&) {
  }
  set_error(GL_OUT_OF_MEMORY);
  return false;
}

GLenum Context::glGetError() {
  PASSIM_ENTRY_RET(GL_NO_ERROR)  // between Begin/End: INVALID_OPERATION, returns 0
  GLenum e = error_;
  error_ = GL_NO_ERROR;
  return e;
}

void Context::warn_once(const std::string& message) {
  if (std::find(warnings_.begin(), warnings_.end(), message) == warnings_.end()) warnings_.push_back(message);
}
// ---------------------------------------------------------------- enables

bool Context::set_capability(GLenum cap, bool v) {
  if (cap >= GL_LIGHT0 && cap < GL_LIGHT0 + static_cast<GLenum>(lighting_.lights.size())) {
    lighting_.lights[cap - GL_LIGHT0].enabled = v;
    return true;
  }
  if (cap >= GL_CLIP_PLANE0 && cap < GL_CLIP_PLANE0 + 6) {
    transform_.clip_enabled[cap - GL_CLIP_PLANE0] = v;
    return true;
  }
  switch (cap) {
    case GL_LIGHTING: lighting_.enabled = v; return true;
    case GL_COLOR_MATERIAL:
      lighting_.color_material = v;
      if (v) apply_color_material();
      return true;
    case GL_NORMALIZE: transform_.normalize = v; return true;
    case GL_RESCALE_NORMAL: transform_.rescale_normal = v; return true;
    case GL_CULL_FACE: polygon_.cull_enabled = v; return true;
    case GL_POLYGON_OFFSET_FILL: polygon_.offset_fill = v; return true;
    case GL_POLYGON_OFFSET_LINE: polygon_.offset_line = v; return true;
    case GL_POLYGON_OFFSET_POINT: polygon_.offset_point = v; return true;
    case GL_LINE_STIPPLE: polygon_.line_stipple = v; return true;
    case GL_SCISSOR_TEST: fragment_.scissor_enabled = v; return true;
    case GL_ALPHA_TEST: fragment_.alpha_test = v; return true;
    case GL_STENCIL_TEST: fragment_.stencil_test = v; return true;
    case GL_DEPTH_TEST: fragment_.depth_test = v; return true;
    case GL_BLEND: fragment_.blend = v; return true;
    case GL_DITHER: fragment_.dither = v; return true;  // A3: no effect on the bits
    case GL_COLOR_LOGIC_OP: fragment_.logic_op_enabled = v; return true;
    case GL_FOG: fog_.enabled = v; return true;
    case GL_COLOR_TABLE: transfer_.tables[kColorTable].enabled = v; return true;
    case GL_CONVOLUTION_1D: transfer_.convolution_1d = v; return true;
    case GL_CONVOLUTION_2D: transfer_.convolution_2d = v; return true;
    case GL_SEPARABLE_2D: transfer_.separable_2d = v; return true;
    case GL_HISTOGRAM: transfer_.histogram.enabled = v; return true;
    case GL_MINMAX: transfer_.minmax.enabled = v; return true;
    case GL_POST_CONVOLUTION_COLOR_TABLE: transfer_.tables[kPostConvolutionTable].enabled = v; return true;
    case GL_POST_COLOR_MATRIX_COLOR_TABLE: transfer_.tables[kPostColorMatrixTable].enabled = v; return true;
    case GL_TEXTURE_1D: textures_.enabled_1d = v; texturing_enabled_ = textures_.enabled_1d || textures_.enabled_2d; return true;
    case GL_TEXTURE_2D: textures_.enabled_2d = v; texturing_enabled_ = textures_.enabled_1d || textures_.enabled_2d; return true;
    case GL_TEXTURE_GEN_S: case GL_TEXTURE_GEN_T: case GL_TEXTURE_GEN_R: case GL_TEXTURE_GEN_Q:
      textures_.gen[cap - GL_TEXTURE_GEN_S].enabled = v;
      return true;
    // Accepted and stored; their stages come with later work (see docs/status.md).
    case GL_INDEX_LOGIC_OP:
    case GL_POINT_SMOOTH:
    case GL_LINE_SMOOTH:
    case GL_POLYGON_SMOOTH:
    case GL_POLYGON_STIPPLE:
    case GL_TEXTURE_3D:
    case GL_AUTO_NORMAL:
      unmodelled_caps_[cap] = v;
      if (v) warn_once(fmt::format("{} is enabled, but that stage is not modelled yet: it has no effect", enum_name(cap)));
      return true;
    default: return false;
  }
}

void Context::glEnable(GLenum cap) {
  PASSIM_ENTRY(cap)
  if (!set_capability(cap, true)) set_error(GL_INVALID_ENUM);
}

void Context::glDisable(GLenum cap) {
  PASSIM_ENTRY(cap)
  if (!set_capability(cap, false)) set_error(GL_INVALID_ENUM);
}

// §6.1.5: the implementation's strings, static for the context's life. passim names itself
// and the machine profile it models; the extensions are those it models (docs/status.md).
const GLubyte* Context::glGetString(GLenum name) {
  PASSIM_ENTRY_RET(nullptr, name)
  static const std::string vendor = "passim", version = "1.2 passim",
                           extensions = "GL_ARB_imaging GL_ARB_depth_texture GL_ARB_shadow GL_EXT_debug_marker "
                                        "GL_SGIX_depth_texture GL_SGIX_shadow GL_SGIX_shadow_ambient";
  const std::string* text = nullptr;
  switch (name) {
    case GL_VENDOR: text = &vendor; break;
    case GL_RENDERER: text = &profile_.name; break;
    case GL_VERSION: text = &version; break;
    case GL_EXTENSIONS: text = &extensions; break;
    default: set_error(GL_INVALID_ENUM); return nullptr;
  }
  return reinterpret_cast<const GLubyte*>(text->c_str());
}

GLboolean Context::glIsEnabled(GLenum cap) {
  PASSIM_ENTRY_RET(GL_FALSE, cap)
  std::vector<double> v;
  bool is_color = false;
  if (!get_state(cap, v, is_color) || v.size() != 1) {
    set_error(GL_INVALID_ENUM);
    return GL_FALSE;
  }
  return v[0] != 0.0 ? GL_TRUE : GL_FALSE;
}
// ---------------------------------------------------------------- queries (§6.1.2)

bool Context::get_state(GLenum p, std::vector<double>& out, bool& is_color) const {
  auto one = [&](double v) { out = {v}; return true; };
  auto color = [&](const Vec4& c) { out = {c.r, c.g, c.b, c.a}; is_color = true; return true; };
  auto matrix = [&](const Mat4& m) {
    out.clear();
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) out.push_back(m[c][r]);
    return true;
  };
  const FramebufferConfig& cfg = fb_.config;
  const MachineLimits& lim = profile_.limits;
  if (p >= GL_LIGHT0 && p < GL_LIGHT0 + lighting_.lights.size()) return one(lighting_.lights[p - GL_LIGHT0].enabled);
  if (p >= GL_CLIP_PLANE0 && p < GL_CLIP_PLANE0 + 6) return one(transform_.clip_enabled[p - GL_CLIP_PLANE0]);
  if (auto it = unmodelled_caps_.find(p); it != unmodelled_caps_.end()) return one(it->second);
  switch (p) {
    // enables
    case GL_LIGHTING: return one(lighting_.enabled);
    case GL_COLOR_MATERIAL: return one(lighting_.color_material);
    case GL_NORMALIZE: return one(transform_.normalize);
    case GL_RESCALE_NORMAL: return one(transform_.rescale_normal);
    case GL_CULL_FACE: return one(polygon_.cull_enabled);
    case GL_POLYGON_OFFSET_FILL: return one(polygon_.offset_fill);
    case GL_POLYGON_OFFSET_LINE: return one(polygon_.offset_line);
    case GL_POLYGON_OFFSET_POINT: return one(polygon_.offset_point);
    case GL_SCISSOR_TEST: return one(fragment_.scissor_enabled);
    case GL_ALPHA_TEST: return one(fragment_.alpha_test);
    case GL_STENCIL_TEST: return one(fragment_.stencil_test);
    case GL_DEPTH_TEST: return one(fragment_.depth_test);
    case GL_BLEND: return one(fragment_.blend);
    case GL_DITHER: return one(fragment_.dither);
    case GL_COLOR_LOGIC_OP: return one(fragment_.logic_op_enabled);
    case GL_TEXTURE_1D: return one(textures_.enabled_1d);
    case GL_TEXTURE_2D: return one(textures_.enabled_2d);
    case GL_TEXTURE_GEN_S: case GL_TEXTURE_GEN_T: case GL_TEXTURE_GEN_R: case GL_TEXTURE_GEN_Q:
      return one(textures_.gen[p - GL_TEXTURE_GEN_S].enabled);
    case GL_TEXTURE_BINDING_1D: return one(textures_.bound_1d);
    case GL_TEXTURE_BINDING_2D: return one(textures_.bound_2d);
    case GL_UNPACK_ALIGNMENT: return one(pixel_store_.unpack.alignment);
    case GL_UNPACK_ROW_LENGTH: return one(pixel_store_.unpack.row_length);
    case GL_UNPACK_SKIP_ROWS: return one(pixel_store_.unpack.skip_rows);
    case GL_UNPACK_SKIP_PIXELS: return one(pixel_store_.unpack.skip_pixels);
    case GL_UNPACK_SWAP_BYTES: return one(pixel_store_.unpack.swap_bytes);
    case GL_UNPACK_LSB_FIRST: return one(pixel_store_.unpack.lsb_first);
    case GL_PACK_ALIGNMENT: return one(pixel_store_.pack.alignment);
    case GL_PACK_ROW_LENGTH: return one(pixel_store_.pack.row_length);
    case GL_PACK_SKIP_ROWS: return one(pixel_store_.pack.skip_rows);
    case GL_PACK_SKIP_PIXELS: return one(pixel_store_.pack.skip_pixels);
    case GL_PACK_SWAP_BYTES: return one(pixel_store_.pack.swap_bytes);
    case GL_PACK_LSB_FIRST: return one(pixel_store_.pack.lsb_first);
    case GL_INDEX_LOGIC_OP: case GL_POINT_SMOOTH: case GL_LINE_SMOOTH: case GL_POLYGON_SMOOTH:
      return one(0.0);  // never enabled (unmodelled_caps_ holds them once set)
    case GL_FOG: return one(fog_.enabled);
    case GL_FOG_MODE: return one(fog_.mode);
    case GL_FOG_DENSITY: return one(fog_.density);
    case GL_FOG_START: return one(fog_.start);
    case GL_FOG_END: return one(fog_.end);
    case GL_FOG_COLOR: return color(fog_.color);
    case GL_LINE_STIPPLE: return one(polygon_.line_stipple);
    case GL_POLYGON_STIPPLE: return one(0.0);
    case GL_COLOR_TABLE: return one(transfer_.tables[kColorTable].enabled);
    case GL_POST_CONVOLUTION_COLOR_TABLE: return one(transfer_.tables[kPostConvolutionTable].enabled);
    case GL_POST_COLOR_MATRIX_COLOR_TABLE: return one(transfer_.tables[kPostColorMatrixTable].enabled);
    case GL_CONVOLUTION_1D: return one(transfer_.convolution_1d);
    case GL_CONVOLUTION_2D: return one(transfer_.convolution_2d);
    case GL_SEPARABLE_2D: return one(transfer_.separable_2d);
    case GL_HISTOGRAM: return one(transfer_.histogram.enabled);
    case GL_MINMAX: return one(transfer_.minmax.enabled);
    case GL_TEXTURE_3D: case GL_AUTO_NORMAL:
      return one(0.0);
    // transformation
    case GL_MATRIX_MODE: return one(transform_.matrix_mode);
    case GL_MODELVIEW_MATRIX: return matrix(transform_.modelview.back());
    case GL_PROJECTION_MATRIX: return matrix(transform_.projection.back());
    case GL_TEXTURE_MATRIX: return matrix(transform_.texture.back());
    case GL_COLOR_MATRIX: return matrix(transform_.color.back());
    case GL_MODELVIEW_STACK_DEPTH: return one(static_cast<double>(transform_.modelview.size()));
    case GL_PROJECTION_STACK_DEPTH: return one(static_cast<double>(transform_.projection.size()));
    case GL_TEXTURE_STACK_DEPTH: return one(static_cast<double>(transform_.texture.size()));
    case GL_COLOR_MATRIX_STACK_DEPTH: return one(static_cast<double>(transform_.color.size()));
    case GL_VIEWPORT: out = {double(viewport_.x), double(viewport_.y), double(viewport_.width), double(viewport_.height)}; return true;
    case GL_DEPTH_RANGE: out = {viewport_.near_val, viewport_.far_val}; return true;
    // limits
    case GL_MAX_MODELVIEW_STACK_DEPTH: return one(lim.max_modelview_stack);
    case GL_MAX_PROJECTION_STACK_DEPTH: return one(lim.max_projection_stack);
    case GL_MAX_TEXTURE_STACK_DEPTH: return one(lim.max_texture_stack);
    case GL_MAX_COLOR_MATRIX_STACK_DEPTH: return one(lim.max_color_matrix_stack);
    case GL_MAX_VIEWPORT_DIMS: out = {double(lim.max_viewport_size), double(lim.max_viewport_size)}; return true;
    case GL_MAX_LIGHTS: return one(lim.max_lights);
    case GL_MAX_CLIP_PLANES: return one(lim.max_clip_planes);
    case GL_MAX_LIST_NESTING: return one(lim.max_list_nesting);
    case GL_MAX_TEXTURE_SIZE: return one(lim.max_texture_size);
    case GL_SUBPIXEL_BITS: return one(lim.subpixel_bits);
    case GL_MAX_ATTRIB_STACK_DEPTH: return one(lim.max_attrib_stack);
    case GL_MAX_CLIENT_ATTRIB_STACK_DEPTH: return one(lim.max_client_attrib_stack);
    case GL_ATTRIB_STACK_DEPTH: return one(static_cast<double>(attrib_stack_.size()));
    case GL_CLIENT_ATTRIB_STACK_DEPTH: return one(static_cast<double>(client_attrib_stack_.size()));
    // hints (Table 6.25)
    case GL_PERSPECTIVE_CORRECTION_HINT: return one(hints_.perspective_correction);
    case GL_POINT_SMOOTH_HINT: return one(hints_.point_smooth);
    case GL_LINE_SMOOTH_HINT: return one(hints_.line_smooth);
    case GL_POLYGON_SMOOTH_HINT: return one(hints_.polygon_smooth);
    case GL_FOG_HINT: return one(hints_.fog);
    // framebuffer
    case GL_RED_BITS: return one(cfg.color_bits[0]);
    case GL_GREEN_BITS: return one(cfg.color_bits[1]);
    case GL_BLUE_BITS: return one(cfg.color_bits[2]);
    case GL_ALPHA_BITS: return one(cfg.color_bits[3]);
    case GL_DEPTH_BITS: return one(cfg.depth_bits);
    case GL_STENCIL_BITS: return one(cfg.stencil_bits);
    case GL_ACCUM_RED_BITS: case GL_ACCUM_GREEN_BITS: case GL_ACCUM_BLUE_BITS: case GL_ACCUM_ALPHA_BITS:
      return one(cfg.accum_bits);
    case GL_DOUBLEBUFFER: return one(cfg.double_buffer);
    case GL_STEREO: return one(0.0);
    case GL_RGBA_MODE: return one(1.0);
    case GL_AUX_BUFFERS: return one(0.0);
    case GL_DRAW_BUFFER: return one(fb_control_.draw_buffer);
    case GL_READ_BUFFER: return one(pixel_.read_buffer);
    case GL_COLOR_WRITEMASK:
      out = {double(fb_control_.color_mask[0]), double(fb_control_.color_mask[1]), double(fb_control_.color_mask[2]),
             double(fb_control_.color_mask[3])};
      return true;
    case GL_DEPTH_WRITEMASK: return one(fb_control_.depth_mask);
    case GL_STENCIL_WRITEMASK: return one(fb_control_.stencil_writemask & max_code(cfg.stencil_bits));
    case GL_COLOR_CLEAR_VALUE: return color(fb_control_.clear_color);
    case GL_DEPTH_CLEAR_VALUE: return one(fb_control_.clear_depth);
    case GL_STENCIL_CLEAR_VALUE: return one(fb_control_.clear_stencil);
    case GL_ACCUM_CLEAR_VALUE: return color(fb_control_.clear_accum);
    // fragment operations
    case GL_SCISSOR_BOX:
      out = {double(fragment_.scissor_x), double(fragment_.scissor_y), double(fragment_.scissor_width),
             double(fragment_.scissor_height)};
      return true;
    case GL_ALPHA_TEST_FUNC: return one(fragment_.alpha_func);
    case GL_ALPHA_TEST_REF: is_color = true; return one(fragment_.alpha_ref);
    case GL_STENCIL_FUNC: return one(fragment_.stencil_func);
    case GL_STENCIL_REF: return one(fragment_.stencil_ref);
    case GL_STENCIL_VALUE_MASK: return one(fragment_.stencil_value_mask & max_code(cfg.stencil_bits));
    case GL_STENCIL_FAIL: return one(fragment_.stencil_fail);
    case GL_STENCIL_PASS_DEPTH_FAIL: return one(fragment_.stencil_depth_fail);
    case GL_STENCIL_PASS_DEPTH_PASS: return one(fragment_.stencil_depth_pass);
    case GL_DEPTH_FUNC: return one(fragment_.depth_func);
    case GL_BLEND_SRC: return one(fragment_.blend_src);
    case GL_BLEND_DST: return one(fragment_.blend_dst);
    case GL_BLEND_EQUATION: return one(fragment_.blend_equation);
    case GL_BLEND_COLOR: return color(fragment_.blend_color);
    case GL_LOGIC_OP_MODE: return one(fragment_.logic_op);
    // rasterization
    case GL_CULL_FACE_MODE: return one(polygon_.cull_face);
    case GL_FRONT_FACE: return one(polygon_.front_face);
    case GL_POLYGON_MODE: out = {double(polygon_.mode_front), double(polygon_.mode_back)}; return true;
    case GL_POLYGON_OFFSET_FACTOR: return one(polygon_.offset_factor);
    case GL_POLYGON_OFFSET_UNITS: return one(polygon_.offset_units);
    case GL_POINT_SIZE: return one(polygon_.point_size);
    case GL_LINE_WIDTH: return one(polygon_.line_width);
    case GL_LINE_STIPPLE_PATTERN: return one(polygon_.stipple_pattern);
    case GL_LINE_STIPPLE_REPEAT: return one(polygon_.stipple_repeat);
    // lighting and current values
    case GL_SHADE_MODEL: return one(lighting_.shade_model);
    case GL_LIGHT_MODEL_AMBIENT: return color(lighting_.model_ambient);
    case GL_LIGHT_MODEL_LOCAL_VIEWER: return one(lighting_.local_viewer);
    case GL_LIGHT_MODEL_TWO_SIDE: return one(lighting_.two_side);
    case GL_LIGHT_MODEL_COLOR_CONTROL: return one(lighting_.color_control);
    case GL_COLOR_MATERIAL_FACE: return one(lighting_.color_material_face);
    case GL_COLOR_MATERIAL_PARAMETER: return one(lighting_.color_material_mode);
    case GL_CURRENT_COLOR: return color(current_.color);
    case GL_EDGE_FLAG: return one(current_.edge_flag);
    case GL_CURRENT_NORMAL: out = {current_.normal.x, current_.normal.y, current_.normal.z}; return true;
    case GL_CURRENT_TEXTURE_COORDS:
      out = {current_.texcoord.s, current_.texcoord.t, current_.texcoord.p, current_.texcoord.q};
      return true;
    // §2.12: the raster position (window coordinates, z in [0, 1], clip w) and its validity.
    case GL_CURRENT_RASTER_POSITION:
      out = {raster_.window.x, raster_.window.y, raster_.window.z, raster_.window.w};
      return true;
    case GL_CURRENT_RASTER_POSITION_VALID: return one(raster_.valid);
    case GL_CURRENT_RASTER_COLOR: return color(raster_.color);
    // pixel transfer and zoom (Tables 6.17-6.18)
    case GL_ZOOM_X: return one(zoom_x_);
    case GL_ZOOM_Y: return one(zoom_y_);
    case GL_MAP_COLOR: return one(transfer_.map_color);
    case GL_MAP_STENCIL: return one(transfer_.map_stencil);
    case GL_INDEX_SHIFT: return one(transfer_.index_shift);
    case GL_INDEX_OFFSET: return one(transfer_.index_offset);
    case GL_RED_SCALE: return one(transfer_.scale.r);
    case GL_GREEN_SCALE: return one(transfer_.scale.g);
    case GL_BLUE_SCALE: return one(transfer_.scale.b);
    case GL_ALPHA_SCALE: return one(transfer_.scale.a);
    case GL_RED_BIAS: return one(transfer_.bias.r);
    case GL_GREEN_BIAS: return one(transfer_.bias.g);
    case GL_BLUE_BIAS: return one(transfer_.bias.b);
    case GL_ALPHA_BIAS: return one(transfer_.bias.a);
    case GL_DEPTH_SCALE: return one(transfer_.depth_scale);
    case GL_DEPTH_BIAS: return one(transfer_.depth_bias);
    case GL_POST_CONVOLUTION_RED_SCALE: return one(transfer_.post_convolution_scale.r);
    case GL_POST_CONVOLUTION_GREEN_SCALE: return one(transfer_.post_convolution_scale.g);
    case GL_POST_CONVOLUTION_BLUE_SCALE: return one(transfer_.post_convolution_scale.b);
    case GL_POST_CONVOLUTION_ALPHA_SCALE: return one(transfer_.post_convolution_scale.a);
    case GL_POST_CONVOLUTION_RED_BIAS: return one(transfer_.post_convolution_bias.r);
    case GL_POST_CONVOLUTION_GREEN_BIAS: return one(transfer_.post_convolution_bias.g);
    case GL_POST_CONVOLUTION_BLUE_BIAS: return one(transfer_.post_convolution_bias.b);
    case GL_POST_CONVOLUTION_ALPHA_BIAS: return one(transfer_.post_convolution_bias.a);
    case GL_POST_COLOR_MATRIX_RED_SCALE: return one(transfer_.post_color_matrix_scale.r);
    case GL_POST_COLOR_MATRIX_GREEN_SCALE: return one(transfer_.post_color_matrix_scale.g);
    case GL_POST_COLOR_MATRIX_BLUE_SCALE: return one(transfer_.post_color_matrix_scale.b);
    case GL_POST_COLOR_MATRIX_ALPHA_SCALE: return one(transfer_.post_color_matrix_scale.a);
    case GL_POST_COLOR_MATRIX_RED_BIAS: return one(transfer_.post_color_matrix_bias.r);
    case GL_POST_COLOR_MATRIX_GREEN_BIAS: return one(transfer_.post_color_matrix_bias.g);
    case GL_POST_COLOR_MATRIX_BLUE_BIAS: return one(transfer_.post_color_matrix_bias.b);
    case GL_POST_COLOR_MATRIX_ALPHA_BIAS: return one(transfer_.post_color_matrix_bias.a);
    // lists and arrays
    case GL_LIST_BASE: return one(list_base_);
    case GL_LIST_INDEX: return one(compiling_list_);
    case GL_LIST_MODE: return one(compiling_list_ ? compile_mode_ : 0);
    case GL_VERTEX_ARRAY: return one(arrays_.vertex.enabled);
    case GL_NORMAL_ARRAY: return one(arrays_.normal.enabled);
    case GL_COLOR_ARRAY: return one(arrays_.color.enabled);
    case GL_TEXTURE_COORD_ARRAY: return one(arrays_.texcoord.enabled);
    case GL_EDGE_FLAG_ARRAY: return one(arrays_.edge_flag.enabled);
    default: return false;
  }
}

namespace {
// §6.1.2: conversion of state values to the type a Get command returns.
GLint to_integer(double v, bool is_color) {
  if (is_color) {
    // Colours map linearly: 1.0 to the largest positive integer, -1.0 to the most negative.
    const double m = 2147483647.0;
    return static_cast<GLint>(round_half_up(clamp_nan_low(v, -1.0, 1.0) * m));
  }
  if (!(v == v)) return 0;
  return static_cast<GLint>(std::clamp(round_half_up(v), -2147483648.0, 2147483647.0));
}
}  // namespace

std::uint64_t Context::state_output_elements(GLenum pname) const {
  std::vector<double> v;
  bool is_color = false;
  return get_state(pname, v, is_color) ? v.size() : 0;
}

void Context::glGetIntegerv(GLenum pname, GLint* params) {
  PASSIM_ENTRY(pname, params)
  std::vector<double> v;
  bool is_color = false;
  if (!get_state(pname, v, is_color)) return set_error(GL_INVALID_ENUM);
  for (std::size_t k = 0; k < v.size(); ++k) params[k] = to_integer(v[k], is_color);
}

void Context::glGetFloatv(GLenum pname, GLfloat* params) {
  PASSIM_ENTRY(pname, params)
  std::vector<double> v;
  bool is_color = false;
  if (!get_state(pname, v, is_color)) return set_error(GL_INVALID_ENUM);
  for (std::size_t k = 0; k < v.size(); ++k) params[k] = static_cast<GLfloat>(v[k]);
}

void Context::glGetDoublev(GLenum pname, GLdouble* params) {
  PASSIM_ENTRY(pname, params)
  std::vector<double> v;
  bool is_color = false;
  if (!get_state(pname, v, is_color)) return set_error(GL_INVALID_ENUM);
  std::copy(v.begin(), v.end(), params);
}

void Context::glGetBooleanv(GLenum pname, GLboolean* params) {
  PASSIM_ENTRY(pname, params)
  std::vector<double> v;
  bool is_color = false;
  if (!get_state(pname, v, is_color)) return set_error(GL_INVALID_ENUM);
  for (std::size_t k = 0; k < v.size(); ++k) params[k] = v[k] != 0.0 ? GL_TRUE : GL_FALSE;
}

void Context::glHint(GLenum target, GLenum mode) {
  PASSIM_ENTRY(target, mode)
  GLenum* hint = nullptr;
  switch (target) {
    case GL_PERSPECTIVE_CORRECTION_HINT: hint = &hints_.perspective_correction; break;
    case GL_POINT_SMOOTH_HINT: hint = &hints_.point_smooth; break;
    case GL_LINE_SMOOTH_HINT: hint = &hints_.line_smooth; break;
    case GL_POLYGON_SMOOTH_HINT: hint = &hints_.polygon_smooth; break;
    case GL_FOG_HINT: hint = &hints_.fog; break;
    default: return set_error(GL_INVALID_ENUM);
  }
  if (mode != GL_FASTEST && mode != GL_NICEST && mode != GL_DONT_CARE) return set_error(GL_INVALID_ENUM);
  // Hints never change the bits here: the arithmetic is fixed (docs/arithmetic.md); they are
  // kept for the queries and HINT_BIT.
  *hint = mode;
}

void Context::glFlush() { PASSIM_ENTRY() }
void Context::glFinish() { PASSIM_ENTRY() }

}  // namespace passim
