// Context: the attribute stacks (OpenGL 1.2.1 §6.1.14). PushAttrib saves the state of the
// groups its mask names on the server stack, PopAttrib restores the groups the entry saved;
// PushClientAttrib and PopClientAttrib do the same for the client state (vertex arrays, pixel
// storage). The groups are the "Attribute" column of the state tables (§6.2); the mapping of
// each struct of pipeline/state.hpp to them is written out below. A struct that belongs to one
// group is saved whole; a struct whose fields belong to several groups is copied field by
// field, and the number of its fields is asserted beside the copy, so a field added to it
// fails the build here until its group is named.
#include <algorithm>
#include <set>

#include "pipeline/context.hpp"

namespace passim {

namespace {

// to.*m = from.*m for each member m.
template <class S, class... M>
void assign(S& to, const S& from, M S::*... members) {
  ((to.*members = from.*members), ...);
}

// The enables no stage reads yet (Context::unmodelled_caps_), each with its own group
// (Tables 6.9, 6.12, 6.14, 6.26): each is restored by that group and by ENABLE_BIT.
GLbitfield unmodelled_cap_group(GLenum cap) {
  switch (cap) {
    case GL_POINT_SMOOTH: return GL_POINT_BIT;
    case GL_LINE_SMOOTH: return GL_LINE_BIT;
    case GL_POLYGON_SMOOTH: case GL_POLYGON_STIPPLE: return GL_POLYGON_BIT;
    case GL_INDEX_LOGIC_OP: return GL_COLOR_BUFFER_BIT;
    case GL_TEXTURE_3D: return GL_TEXTURE_BIT;
    case GL_AUTO_NORMAL: return GL_EVAL_BIT;
    default: return 0;  // AttribStack.EveryEnableIsRestoredByItsOwnGroup fails for an enable left out
  }
}

// Structs whose fields are split among groups (or are partly not in any group: "—"). When
// one of these fails, the struct has gained or lost a field: give it its group below.
static_assert(field_count<TransformState> == 9, "TransformState changed: map its new field to a group");
static_assert(field_count<PolygonState> == 15, "PolygonState changed: map its new field to a group");
static_assert(field_count<FragmentOpsState> == 25, "FragmentOpsState changed: map its new field to a group");
static_assert(field_count<FramebufferControlState> == 8, "FramebufferControlState changed: map its new field");
static_assert(field_count<TextureState> == 11, "TextureState changed: map its new field to a group");
static_assert(field_count<PixelTransferState> == 24, "PixelTransferState changed: map its new field to a group");
static_assert(field_count<ColorTable> == 6, "ColorTable changed: map its new field to a group");
static_assert(field_count<ConvolutionFilter> == 12, "ConvolutionFilter changed: map its new field to a group");
static_assert(field_count<Histogram> == 5, "Histogram changed: map its new field to a group");
static_assert(field_count<Minmax> == 6, "Minmax changed: map its new field to a group");

// A texture object's parameters: the object without its images (§6.1.14: "the bound
// objects' parameters, not their images"); every other field is a parameter.
TextureObject texture_parameters(TextureObject& object) {
  std::vector<TextureLevel> levels = std::move(object.levels);
  object.levels.clear();
  TextureObject parameters = object;
  object.levels = std::move(levels);
  return parameters;
}
void restore_texture_parameters(TextureObject& object, const TextureObject& parameters) {
  std::vector<TextureLevel> levels = std::move(object.levels);
  const GLenum target = object.target;
  object = parameters;
  object.levels = std::move(levels);
  object.target = target;
}

// Table 6.18: the "pixel" fields of a colour table and of a convolution filter (scale, bias,
// border); their contents, formats and sizes are "—".
void assign_table_parameters(ColorTable& to, const ColorTable& from) {
  assign(to, from, &ColorTable::enabled, &ColorTable::scale, &ColorTable::bias);
}
void assign_filter_parameters(ConvolutionFilter& to, const ConvolutionFilter& from) {
  assign(to, from, &ConvolutionFilter::scale, &ConvolutionFilter::bias, &ConvolutionFilter::border_mode,
         &ConvolutionFilter::border_color);
}
// PIXEL_MODE_BIT's part of Table 6.17-6.18: the transfer modes, scales and biases, the
// imaging enables and parameters. Not the tables' entries, the filters' taps, the histogram's
// counts, the minmax values, their formats and sinks, nor the pixel maps ("—").
void assign_transfer_modes(PixelTransferState& to, const PixelTransferState& from) {
  assign(to, from, &PixelTransferState::scale, &PixelTransferState::bias, &PixelTransferState::depth_scale,
         &PixelTransferState::depth_bias, &PixelTransferState::map_color, &PixelTransferState::map_stencil,
         &PixelTransferState::index_shift, &PixelTransferState::index_offset,
         &PixelTransferState::post_color_matrix_scale, &PixelTransferState::post_color_matrix_bias,
         &PixelTransferState::convolution_1d, &PixelTransferState::convolution_2d, &PixelTransferState::separable_2d,
         &PixelTransferState::post_convolution_scale, &PixelTransferState::post_convolution_bias);
  for (std::size_t k = 0; k < to.tables.size(); ++k) assign_table_parameters(to.tables[k], from.tables[k]);
  assign_filter_parameters(to.filter_1d, from.filter_1d);
  assign_filter_parameters(to.filter_2d, from.filter_2d);
  assign_filter_parameters(to.filter_separable, from.filter_separable);
  to.histogram.enabled = from.histogram.enabled;
  to.minmax.enabled = from.minmax.enabled;
  // Not GL state: color_maps, other_maps ("—"), removed (the what-if study's).
}

}  // namespace

std::vector<GLenum> Context::capabilities() const {
  std::vector<GLenum> caps = {
      GL_LIGHTING, GL_COLOR_MATERIAL, GL_NORMALIZE, GL_RESCALE_NORMAL, GL_CULL_FACE, GL_POLYGON_OFFSET_FILL,
      GL_POLYGON_OFFSET_LINE, GL_POLYGON_OFFSET_POINT, GL_SCISSOR_TEST, GL_ALPHA_TEST, GL_STENCIL_TEST,
      GL_DEPTH_TEST, GL_BLEND, GL_DITHER, GL_COLOR_LOGIC_OP, GL_FOG, GL_COLOR_TABLE, GL_CONVOLUTION_1D,
      GL_CONVOLUTION_2D, GL_SEPARABLE_2D, GL_HISTOGRAM, GL_MINMAX, GL_POST_CONVOLUTION_COLOR_TABLE,
      GL_POST_COLOR_MATRIX_COLOR_TABLE, GL_TEXTURE_1D, GL_TEXTURE_2D, GL_TEXTURE_GEN_S, GL_TEXTURE_GEN_T,
      GL_TEXTURE_GEN_R, GL_TEXTURE_GEN_Q, GL_INDEX_LOGIC_OP, GL_POINT_SMOOTH, GL_LINE_SMOOTH, GL_POLYGON_SMOOTH,
      GL_LINE_STIPPLE, GL_POLYGON_STIPPLE, GL_TEXTURE_3D, GL_AUTO_NORMAL};
  for (std::size_t k = 0; k < lighting_.lights.size(); ++k) caps.push_back(GL_LIGHT0 + static_cast<GLenum>(k));
  for (GLenum k = 0; k < 6; ++k) caps.push_back(GL_CLIP_PLANE0 + k);
  return caps;
}

void Context::save_attribs(ServerAttribs& s) {
  const GLbitfield m = s.mask;
  if (m & GL_CURRENT_BIT) {  // Table 6.2
    s.current = current_;
    s.raster = raster_;
  }
  // Table 6.9: POINT_SIZE (point), LINE_WIDTH (line), the rest (polygon). Copied whole; each
  // group restores its own fields.
  if (m & (GL_POINT_BIT | GL_LINE_BIT | GL_POLYGON_BIT)) s.polygon = polygon_;
  if (m & GL_ENABLE_BIT) {
    for (GLenum cap : capabilities()) {
      std::vector<double> v;
      bool is_color = false;
      get_state(cap, v, is_color);
      s.enables.emplace_back(cap, !v.empty() && v[0] != 0.0);
    }
  }
  s.unmodelled_caps = unmodelled_caps_;
  if (m & GL_LIGHTING_BIT) s.lighting = lighting_;  // Tables 6.7-6.8, SHADE_MODEL
  if (m & GL_FOG_BIT) s.fog = fog_;
  if (m & (GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT | GL_COLOR_BUFFER_BIT | GL_SCISSOR_BIT | GL_ACCUM_BUFFER_BIT)) {
    s.fragment = fragment_;
    s.fb_control = fb_control_;
  }
  if (m & GL_VIEWPORT_BIT) s.viewport = viewport_;
  if (m & GL_TRANSFORM_BIT) {  // Table 6.5 "transform"; the matrices and stacks are "—"
    s.matrix_mode = transform_.matrix_mode;
    s.normalize = transform_.normalize;
    s.rescale_normal = transform_.rescale_normal;
    s.clip_plane = transform_.clip_plane;
    s.clip_enabled = transform_.clip_enabled;
  }
  if (m & GL_HINT_BIT) s.hints = hints_;
  if (m & GL_LIST_BIT) s.list_base = list_base_;
  if (m & GL_PIXEL_MODE_BIT) {
    s.pixel = pixel_;
    s.zoom_x = zoom_x_;
    s.zoom_y = zoom_y_;
    assign_transfer_modes(s.transfer, transfer_);
  }
  if (m & GL_TEXTURE_BIT) {
    s.texture_1d = textures_.enabled_1d;
    s.texture_2d = textures_.enabled_2d;
    s.bound_1d = {textures_.bound_1d, texture_parameters(*texture_for(GL_TEXTURE_1D))};
    s.bound_2d = {textures_.bound_2d, texture_parameters(*texture_for(GL_TEXTURE_2D))};
    s.env_mode = textures_.env_mode;
    s.env_color = textures_.env_color;
    s.gen = textures_.gen;  // coordinate generation, with its enables
    // Not saved: the images (—), the other objects (§6.1.14: unbound objects are neither
    // pushed nor restored), the names glGenTextures reserved (—).
  }
  // EVAL_BIT: of Table 6.26 passim keeps AUTO_NORMAL only (an unmodelled enable); the
  // evaluator maps, their enables and grids are not modelled.
  // POLYGON_STIPPLE_BIT: the stipple pattern is not modelled (its enable is POLYGON_BIT's).
}

void Context::restore_attribs(const ServerAttribs& s) {
  const GLbitfield m = s.mask;
  if (m & GL_CURRENT_BIT) {
    current_ = s.current;
    raster_ = s.raster;
    materials_dirty_ = true;  // a COLOR_MATERIAL vertex reads the current colour
  }
  if (m & GL_POINT_BIT) assign(polygon_, s.polygon, &PolygonState::point_size);
  if (m & GL_LINE_BIT)
    assign(polygon_, s.polygon, &PolygonState::line_width, &PolygonState::line_stipple, &PolygonState::stipple_pattern,
           &PolygonState::stipple_repeat);
  if (m & GL_POLYGON_BIT)
    assign(polygon_, s.polygon, &PolygonState::cull_enabled, &PolygonState::cull_face, &PolygonState::front_face,
           &PolygonState::mode_front, &PolygonState::mode_back, &PolygonState::offset_factor,
           &PolygonState::offset_units, &PolygonState::offset_fill, &PolygonState::offset_line,
           &PolygonState::offset_point);
  // The unmodelled enables of the groups popped (ENABLE_BIT's own pass below covers all).
  std::set<GLenum> unmodelled;
  for (const auto& [cap, value] : s.unmodelled_caps) unmodelled.insert(cap);
  for (const auto& [cap, value] : unmodelled_caps_) unmodelled.insert(cap);
  for (GLenum cap : unmodelled) {
    if (!(unmodelled_cap_group(cap) & m)) continue;
    auto it = s.unmodelled_caps.find(cap);
    if (it != s.unmodelled_caps.end()) unmodelled_caps_[cap] = it->second;
    else unmodelled_caps_.erase(cap);
  }
  if (m & GL_LIGHTING_BIT) {
    lighting_ = s.lighting;
    materials_dirty_ = true;
  }
  if (m & GL_FOG_BIT) fog_ = s.fog;
  // Tables 6.15-6.16.
  if (m & GL_DEPTH_BUFFER_BIT) {
    assign(fragment_, s.fragment, &FragmentOpsState::depth_test, &FragmentOpsState::depth_func);
    assign(fb_control_, s.fb_control, &FramebufferControlState::depth_mask, &FramebufferControlState::clear_depth);
  }
  if (m & GL_STENCIL_BUFFER_BIT) {
    assign(fragment_, s.fragment, &FragmentOpsState::stencil_test, &FragmentOpsState::stencil_func,
           &FragmentOpsState::stencil_ref, &FragmentOpsState::stencil_value_mask, &FragmentOpsState::stencil_fail,
           &FragmentOpsState::stencil_depth_fail, &FragmentOpsState::stencil_depth_pass);
    assign(fb_control_, s.fb_control, &FramebufferControlState::stencil_writemask,
           &FramebufferControlState::clear_stencil);
  }
  if (m & GL_COLOR_BUFFER_BIT) {
    assign(fragment_, s.fragment, &FragmentOpsState::alpha_test, &FragmentOpsState::alpha_func,
           &FragmentOpsState::alpha_ref, &FragmentOpsState::blend, &FragmentOpsState::blend_src,
           &FragmentOpsState::blend_dst, &FragmentOpsState::blend_equation, &FragmentOpsState::blend_color,
           &FragmentOpsState::dither, &FragmentOpsState::logic_op_enabled, &FragmentOpsState::logic_op);
    assign(fb_control_, s.fb_control, &FramebufferControlState::draw_buffer, &FramebufferControlState::color_mask,
           &FramebufferControlState::clear_color);
    draw_buffer_ids_ = buffers_named(fb_control_.draw_buffer);  // named an existing buffer when pushed
  }
  if (m & GL_SCISSOR_BIT)
    assign(fragment_, s.fragment, &FragmentOpsState::scissor_enabled, &FragmentOpsState::scissor_x,
           &FragmentOpsState::scissor_y, &FragmentOpsState::scissor_width, &FragmentOpsState::scissor_height);
  if (m & GL_ACCUM_BUFFER_BIT) assign(fb_control_, s.fb_control, &FramebufferControlState::clear_accum);
  if (m & GL_VIEWPORT_BIT) viewport_ = s.viewport;
  if (m & GL_TRANSFORM_BIT) {
    transform_.matrix_mode = s.matrix_mode;
    transform_.normalize = s.normalize;
    transform_.rescale_normal = s.rescale_normal;
    transform_.clip_plane = s.clip_plane;
    transform_.clip_enabled = s.clip_enabled;
  }
  if (m & GL_HINT_BIT) hints_ = s.hints;
  if (m & GL_LIST_BIT) list_base_ = s.list_base;
  if (m & GL_PIXEL_MODE_BIT) {
    pixel_ = s.pixel;
    zoom_x_ = s.zoom_x;
    zoom_y_ = s.zoom_y;
    assign_transfer_modes(transfer_, s.transfer);
  }
  if (m & GL_TEXTURE_BIT) {
    // §6.1.14: the bindings and enables first, then the bound objects' parameters. A name
    // deleted since the push is bound anew, as BindTexture binds an unused name.
    textures_.enabled_1d = s.texture_1d;
    textures_.enabled_2d = s.texture_2d;
    for (const auto& [target, saved] : {std::pair{GL_TEXTURE_1D, &s.bound_1d}, std::pair{GL_TEXTURE_2D, &s.bound_2d}}) {
      (target == GL_TEXTURE_1D ? textures_.bound_1d : textures_.bound_2d) = saved->name;
      TextureObject& object = *texture_for(static_cast<GLenum>(target));
      if (object.target == 0) object.target = static_cast<GLenum>(target);
      restore_texture_parameters(object, saved->parameters);
    }
    textures_.env_mode = s.env_mode;
    textures_.env_color = s.env_color;
    textures_.gen = s.gen;
  }
  // ENABLE_BIT last: every enable as pushed, whichever other groups were popped. Through
  // set_capability, and only where the flag differs, so that what Enable does besides
  // setting the flag (COLOR_MATERIAL's tracking) happens as an Enable would do it.
  if (m & GL_ENABLE_BIT) {
    for (const auto& [cap, value] : s.enables) {
      std::vector<double> v;
      bool is_color = false;
      get_state(cap, v, is_color);
      if ((!v.empty() && v[0] != 0.0) != value) set_capability(cap, value);
    }
  }
  texturing_enabled_ = textures_.enabled_1d || textures_.enabled_2d;
}

void Context::glPushAttrib(GLbitfield mask) {
  PASSIM_ENTRY(mask)
  if (attrib_stack_.size() >= static_cast<std::size_t>(profile_.limits.max_attrib_stack))
    return set_error(GL_STACK_OVERFLOW);
  ServerAttribs saved;
  saved.mask = mask;
  save_attribs(saved);
  attrib_stack_.push_back(std::move(saved));
}

void Context::glPopAttrib() {
  PASSIM_ENTRY()
  if (attrib_stack_.empty()) return set_error(GL_STACK_UNDERFLOW);
  restore_attribs(attrib_stack_.back());
  attrib_stack_.pop_back();
}

void Context::glPushClientAttrib(GLbitfield mask) {
  PASSIM_ENTRY(mask)
  if (client_attrib_stack_.size() >= static_cast<std::size_t>(profile_.limits.max_client_attrib_stack))
    return set_error(GL_STACK_OVERFLOW);
  ClientAttribs saved;
  saved.mask = mask;
  if (mask & GL_CLIENT_PIXEL_STORE_BIT) saved.pixel_store = pixel_store_;  // Table 6.20
  if (mask & GL_CLIENT_VERTEX_ARRAY_BIT) saved.arrays = arrays_;           // Tables 6.6-6.7
  client_attrib_stack_.push_back(saved);
}

void Context::glPopClientAttrib() {
  PASSIM_ENTRY()
  if (client_attrib_stack_.empty()) return set_error(GL_STACK_UNDERFLOW);
  const ClientAttribs& saved = client_attrib_stack_.back();
  if (saved.mask & GL_CLIENT_PIXEL_STORE_BIT) pixel_store_ = saved.pixel_store;
  if (saved.mask & GL_CLIENT_VERTEX_ARRAY_BIT) arrays_ = saved.arrays;
  client_attrib_stack_.pop_back();
}

}  // namespace passim
