// Context: the per-fragment operations' state (§4.1), and the stages each primitive is drawn
// through (texturing, fog, the per-fragment operations) set up from the state.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "client/glu_mipmaps.hpp"
#include "client/pixel_pack.hpp"
#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/accumulate.hpp"
#include "stages/clear.hpp"
#include "stages/kernel_paths.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

// ---------------------------------------------------------------- per-fragment state (§4.1)

namespace {
bool is_compare_func(GLenum f) { return f >= GL_NEVER && f <= GL_ALWAYS; }
bool is_stencil_op(GLenum op) {
  return op == GL_KEEP || op == GL_ZERO || op == GL_REPLACE || op == GL_INCR || op == GL_DECR || op == GL_INVERT;
}
bool is_src_factor(GLenum f) {
  switch (f) {
    case GL_ZERO: case GL_ONE: case GL_DST_COLOR: case GL_ONE_MINUS_DST_COLOR: case GL_SRC_ALPHA:
    case GL_ONE_MINUS_SRC_ALPHA: case GL_DST_ALPHA: case GL_ONE_MINUS_DST_ALPHA: case GL_SRC_ALPHA_SATURATE:
    case GL_CONSTANT_COLOR: case GL_ONE_MINUS_CONSTANT_COLOR: case GL_CONSTANT_ALPHA:
    case GL_ONE_MINUS_CONSTANT_ALPHA: return true;
    default: return false;
  }
}
bool is_dst_factor(GLenum f) {
  switch (f) {
    case GL_ZERO: case GL_ONE: case GL_SRC_COLOR: case GL_ONE_MINUS_SRC_COLOR: case GL_SRC_ALPHA:
    case GL_ONE_MINUS_SRC_ALPHA: case GL_DST_ALPHA: case GL_ONE_MINUS_DST_ALPHA: case GL_CONSTANT_COLOR:
    case GL_ONE_MINUS_CONSTANT_COLOR: case GL_CONSTANT_ALPHA: case GL_ONE_MINUS_CONSTANT_ALPHA: return true;
    default: return false;
  }
}
}  // namespace

void Context::glScissor(GLint x, GLint y, GLsizei width, GLsizei height) {
  PASSIM_ENTRY(x, y, width, height)
  if (width < 0 || height < 0) return set_error(GL_INVALID_VALUE);
  fragment_.scissor_x = x;
  fragment_.scissor_y = y;
  fragment_.scissor_width = width;
  fragment_.scissor_height = height;
}

void Context::glAlphaFunc(GLenum func, GLclampf ref) {
  PASSIM_ENTRY(func, ref)
  if (!is_compare_func(func)) return set_error(GL_INVALID_ENUM);
  fragment_.alpha_func = func;
  fragment_.alpha_ref = clamp_nan_low(ref, 0.0, 1.0);
}

void Context::glStencilFunc(GLenum func, GLint ref, GLuint mask) {
  PASSIM_ENTRY(func, ref, mask)
  if (!is_compare_func(func)) return set_error(GL_INVALID_ENUM);
  fragment_.stencil_func = func;
  fragment_.stencil_ref = ref;
  fragment_.stencil_value_mask = mask;
}

void Context::glStencilOp(GLenum fail, GLenum zfail, GLenum zpass) {
  PASSIM_ENTRY(fail, zfail, zpass)
  if (!is_stencil_op(fail) || !is_stencil_op(zfail) || !is_stencil_op(zpass)) return set_error(GL_INVALID_ENUM);
  fragment_.stencil_fail = fail;
  fragment_.stencil_depth_fail = zfail;
  fragment_.stencil_depth_pass = zpass;
}

void Context::glDepthFunc(GLenum func) {
  PASSIM_ENTRY(func)
  if (!is_compare_func(func)) return set_error(GL_INVALID_ENUM);
  fragment_.depth_func = func;
}

void Context::glBlendFunc(GLenum sfactor, GLenum dfactor) {
  PASSIM_ENTRY(sfactor, dfactor)
  if (!is_src_factor(sfactor) || !is_dst_factor(dfactor)) return set_error(GL_INVALID_ENUM);
  fragment_.blend_src = sfactor;
  fragment_.blend_dst = dfactor;
}

void Context::glBlendEquation(GLenum mode) {
  PASSIM_ENTRY(mode)
  if (mode != GL_FUNC_ADD && mode != GL_FUNC_SUBTRACT && mode != GL_FUNC_REVERSE_SUBTRACT && mode != GL_MIN &&
      mode != GL_MAX)
    return set_error(GL_INVALID_ENUM);
  fragment_.blend_equation = mode;
}

void Context::glBlendColor(GLclampf r, GLclampf g, GLclampf b, GLclampf a) {
  PASSIM_ENTRY(r, g, b, a)
  fragment_.blend_color = Vec4(clamp_nan_low(r, 0, 1), clamp_nan_low(g, 0, 1), clamp_nan_low(b, 0, 1),
                               clamp_nan_low(a, 0, 1));
}

void Context::glLogicOp(GLenum opcode) {
  PASSIM_ENTRY(opcode)
  if (opcode < GL_CLEAR || opcode > GL_SET) return set_error(GL_INVALID_ENUM);
  fragment_.logic_op = opcode;
}
// ---------------------------------------------------------------- per primitive

FragmentStagesSetup Context::fragment_stages_setup(TriangleOptions& options) {
  // The stages a primitive's fragments pass through: [texture] -> [fog] -> per-fragment ops.
  FragmentStagesSetup setup;
  setup.ops = fragment_ops_input();
  // §4.1.5: with the depth test disabled no stage reads a fragment's depth (the stencil test
  // then counts it as passing the depth test and the depth plane is not written), so the
  // rasterizer need not compute it: a target without depth bits fills zeros.
  setup.target = RasterTarget{fb_.config.width, fb_.config.height, profile_.limits.subpixel_bits,
                              fragment_.depth_test ? fb_.config.depth_bits : 0, fragment_bits_};
  setup.fog = options.fog = fog_.enabled;
  setup.fog_state = fog_;
  options.texcoords = false;
  options.lod = false;
  if (!texturing_enabled_) return setup;
  // §3.8.15: TEXTURE_2D takes precedence over TEXTURE_1D; an incomplete texture disables texturing.
  const GLenum target = textures_.enabled_2d ? GL_TEXTURE_2D : GL_TEXTURE_1D;
  const int dims = target == GL_TEXTURE_2D ? 2 : 1;
  const TextureObject& tex = *texture_for(target);
  const int last = texture_complete_levels(tex, dims);
  if (last < 0) {
    warn_once(fmt::format("{} is enabled but its texture is incomplete: texturing is disabled (§3.8.10)",
                          enum_name(target)));
    return setup;
  }
  const TextureLevel& base = tex.levels[static_cast<std::size_t>(tex.base_level)];
  options.texcoords = true;
  options.lod = texture_needs_lod(tex);
  options.lod_width = base.width - 2 * base.border;
  options.lod_height = dims == 2 ? base.height - 2 * base.border : 1;
  options.min_lod = tex.min_lod;
  options.max_lod = tex.max_lod;
  // The texture stage reads t only for a 2D texture and r only for a depth comparison.
  options.texcoords_used = (tex.compare_sgix || tex.compare_mode == GL_COMPARE_R_TO_TEXTURE) ? 3 : dims;
  setup.texture = true;
  setup.texture_setup = TextureStageSetup{
      &tex, dims, last, textures_.env_mode, textures_.env_color, fragment_bits_, profile_.arithmetic.texture_filter_8_8};
  return setup;
}

const FragmentStagesSetup& Context::primitive_stages_setup(TriangleOptions& options) {
  if (!primitive_setup_valid_) {
    scratch_->primitive_options = TriangleOptions{};
    scratch_->primitive_setup = fragment_stages_setup(scratch_->primitive_options);
    if (!scratch_->lanes) scratch_->stages.connect(scratch_->primitive_setup);
    primitive_setup_valid_ = true;
  }
  options = scratch_->primitive_options;
  return scratch_->primitive_setup;
}

FragmentOpsInput Context::fragment_ops_input() const {
  return FragmentOpsInput{&fragment_, &fb_control_, &draw_buffer_ids_, &fragment_bits_, &profile_.arithmetic};
}

void Context::prepare_fragment_stages(TriangleOptions& options) {
  primitive_setup_valid_ = false;  // the stages are connected to another setup now
  scratch_->stages.connect(fragment_stages_setup(options));
}

FragmentSink& Context::fragment_sink() { return *scratch_->stages.first; }

}  // namespace passim
