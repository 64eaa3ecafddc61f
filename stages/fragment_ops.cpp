#include "stages/fragment_ops.hpp"

#include <algorithm>
#include <cstring>
#include <type_traits>

#include "pipeline/fixed_point.hpp"
#include "stages/kernel_paths.hpp"


namespace passim {

bool compare(GLenum func, std::uint32_t incoming, std::uint32_t stored) {
  switch (func) {
    case GL_NEVER: return false;
    case GL_LESS: return incoming < stored;
    case GL_EQUAL: return incoming == stored;
    case GL_LEQUAL: return incoming <= stored;
    case GL_GREATER: return incoming > stored;
    case GL_NOTEQUAL: return incoming != stored;
    case GL_GEQUAL: return incoming >= stored;
    default: return true;  // GL_ALWAYS
  }
}

namespace {
// blend_component, inlined into the per-fragment loop (the exported function calls it).
[[gnu::always_inline]] inline double blend_one(GLenum equation, double s, double d, double sf, double df,
                                               int product_bits) {
  auto product = [product_bits](double c, double f) { return product_bits > 0 ? quantise(c * f, product_bits) : c * f; };
  switch (equation) {
    case GL_FUNC_SUBTRACT: return product(s, sf) - product(d, df);
    case GL_FUNC_REVERSE_SUBTRACT: return product(d, df) - product(s, sf);
    case GL_MIN: return std::min(s, d);  // factors ignored (ARB_imaging)
    case GL_MAX: return std::max(s, d);
    default: return product(s, sf) + product(d, df);  // GL_FUNC_ADD
  }
}
}  // namespace

double blend_component(GLenum equation, double s, double d, double sf, double df, int product_bits) {
  return blend_one(equation, s, d, sf, df, product_bits);
}

std::uint32_t logic_op(GLenum op, std::uint32_t s, std::uint32_t d, std::uint32_t mask) {
  std::uint32_t r;
  switch (op) {
    case GL_CLEAR: r = 0; break;
    case GL_AND: r = s & d; break;
    case GL_AND_REVERSE: r = s & ~d; break;
    case GL_COPY: r = s; break;
    case GL_AND_INVERTED: r = ~s & d; break;
    case GL_NOOP: r = d; break;
    case GL_XOR: r = s ^ d; break;
    case GL_OR: r = s | d; break;
    case GL_NOR: r = ~(s | d); break;
    case GL_EQUIV: r = ~(s ^ d); break;
    case GL_INVERT: r = ~d; break;
    case GL_OR_REVERSE: r = s | ~d; break;
    case GL_COPY_INVERTED: r = ~s; break;
    case GL_OR_INVERTED: r = ~s | d; break;
    case GL_NAND: r = ~(s & d); break;
    case GL_SET: r = ~0u; break;
    default: r = s; break;
  }
  return r & mask;
}

namespace {

// §4.1.6 Table 4.1-4.2: the factor for one component c (0-3) of a fragment.
[[gnu::always_inline]] inline double blend_factor(GLenum f, int c, const double src[4], const double dst[4],
                                                  const double constant[4]) {
  switch (f) {
    case GL_ZERO: return 0.0;
    case GL_ONE: return 1.0;
    case GL_SRC_COLOR: return src[c];
    case GL_ONE_MINUS_SRC_COLOR: return 1.0 - src[c];
    case GL_DST_COLOR: return dst[c];
    case GL_ONE_MINUS_DST_COLOR: return 1.0 - dst[c];
    case GL_SRC_ALPHA: return src[3];
    case GL_ONE_MINUS_SRC_ALPHA: return 1.0 - src[3];
    case GL_DST_ALPHA: return dst[3];
    case GL_ONE_MINUS_DST_ALPHA: return 1.0 - dst[3];
    case GL_CONSTANT_COLOR: return constant[c];
    case GL_ONE_MINUS_CONSTANT_COLOR: return 1.0 - constant[c];
    case GL_CONSTANT_ALPHA: return constant[3];
    case GL_ONE_MINUS_CONSTANT_ALPHA: return 1.0 - constant[3];
    case GL_SRC_ALPHA_SATURATE: return c == 3 ? 1.0 : std::min(src[3], 1.0 - dst[3]);
    default: return 0.0;
  }
}

std::uint32_t stencil_apply(GLenum op, std::uint32_t value, std::uint32_t ref, std::uint32_t max) {
  switch (op) {
    case GL_ZERO: return 0;
    case GL_REPLACE: return ref;
    case GL_INCR: return value < max ? value + 1 : max;  // saturating in GL 1.2
    case GL_DECR: return value > 0 ? value - 1 : 0;
    case GL_INVERT: return ~value & max;
    default: return value;  // GL_KEEP
  }
}


// Depth test without stencil, one loop per comparison function so the compare is inlined.
template <class Cmp>
std::uint64_t depth_loop(Cmp cmp, bool write, const FragmentSpan& span, int begin, int end, std::uint32_t* stored) {
  std::uint64_t killed = 0;
  for (int i = begin; i < end; ++i) {
    if (!span.live[i]) continue;
    const std::uint32_t z = span.depth[i];
    if (cmp(z, stored[i])) {
      if (write) stored[i] = z;
    } else {
      span.live[i] = 0;
      ++killed;
    }
  }
  return killed;
}

}  // namespace

std::uint64_t blend_span_reals_scalar(const RealBlend& b, const std::uint8_t* live, const std::uint16_t* src,
                                      std::uint16_t* dst, int begin, int end) {
  // Code -> real tables for the widths (k/(2^n − 1); a 0-bit channel reads 1: absent alpha).
  const double* src_values[4];
  const double* dst_values[4];
  for (int k = 0; k < 4; ++k) {
    src_values[k] = b.src_bits[k] ? code_values(b.src_bits[k]) : nullptr;
    dst_values[k] = b.dst_bits[k] ? code_values(b.dst_bits[k]) : nullptr;
  }
  std::uint64_t blended = 0;
  for (int i = begin; i < end; ++i) {
    if (!live[i]) continue;
    ++blended;
    std::uint16_t* d = dst + 4 * i;
    const std::uint16_t* s = src + 4 * i;
    double sv[4], dv[4];
    for (int k = 0; k < 4; ++k) {
      sv[k] = src_values[k] ? src_values[k][s[k]] : 1.0;
      dv[k] = dst_values[k] ? dst_values[k][d[k]] : 1.0;
    }
    for (int k = 0; k < 4; ++k) {
      if (!b.written[k]) continue;
      const double sf = blend_factor(b.src_factor, k, sv, dv, b.constant);
      const double df = blend_factor(b.dst_factor, k, sv, dv, b.constant);
      const int product_bits = b.products_rounded ? b.dst_bits[k] : 0;
      d[k] = static_cast<std::uint16_t>(
          float_to_fixed(blend_one(b.equation, sv[k], dv[k], sf, df, product_bits), b.dst_bits[k]));
    }
  }
  return blended;
}

std::uint64_t FragmentOps::depth_only(GLenum func, bool write, const FragmentSpan& span, int begin, int end,
                                      std::uint32_t* stored, std::int64_t tested_hint, Counters& counters) {
  std::uint64_t tested = static_cast<std::uint64_t>(end - begin);
  if (tested_hint >= 0) tested = static_cast<std::uint64_t>(tested_hint);
  else {
    tested = 0;
    for (int i = begin; i < end; ++i) tested += span.live[i];
  }
  std::uint64_t killed = 0;
  switch (func) {
    case GL_NEVER: killed = depth_loop([](std::uint32_t, std::uint32_t) { return false; }, write, span, begin, end, stored); break;
    case GL_LESS: killed = depth_loop([](std::uint32_t a, std::uint32_t b) { return a < b; }, write, span, begin, end, stored); break;
    case GL_EQUAL: killed = depth_loop([](std::uint32_t a, std::uint32_t b) { return a == b; }, write, span, begin, end, stored); break;
    case GL_LEQUAL: killed = depth_loop([](std::uint32_t a, std::uint32_t b) { return a <= b; }, write, span, begin, end, stored); break;
    case GL_GREATER: killed = depth_loop([](std::uint32_t a, std::uint32_t b) { return a > b; }, write, span, begin, end, stored); break;
    case GL_NOTEQUAL: killed = depth_loop([](std::uint32_t a, std::uint32_t b) { return a != b; }, write, span, begin, end, stored); break;
    case GL_GEQUAL: killed = depth_loop([](std::uint32_t a, std::uint32_t b) { return a >= b; }, write, span, begin, end, stored); break;
    default: killed = depth_loop([](std::uint32_t, std::uint32_t) { return true; }, write, span, begin, end, stored); break;
  }
  const std::uint64_t bits = static_cast<std::uint64_t>(fb_.config.depth_bits);
  counters.depth_bits_read += tested * bits;
  if (write) counters.depth_bits_written += (tested - killed) * bits;
  counters.killed_depth += killed;
  return killed;
}

std::uint64_t FragmentOps::stencil_and_depth(const FragmentOpsState& ops, const FramebufferControlState& ctl,
                                             const FragmentSpan& span, int begin, int end, std::size_t row_base,
                                             bool depth_on, Counters& counters) {
  const FramebufferConfig& cfg = fb_.config;
  const std::uint32_t smax = max_code(cfg.stencil_bits);
  const std::uint32_t sref = static_cast<std::uint32_t>(std::clamp<std::int64_t>(ops.stencil_ref, 0, smax));
  const std::uint32_t smask = ops.stencil_value_mask & smax;
  const std::uint32_t swrite = ctl.stencil_writemask & smax;
  std::uint64_t killed = 0;
  auto update = [&](std::size_t p, std::uint32_t stencil, GLenum op) {
    const std::uint32_t s = stencil_apply(op, stencil, sref, smax);
    if (s != stencil && swrite) {
      fb_.stencil[p] = static_cast<std::uint8_t>((stencil & ~swrite) | (s & swrite));
      counters.stencil_bits_written += static_cast<std::uint64_t>(cfg.stencil_bits);
    }
  };
  for (int i = begin; i < end; ++i) {
    if (!span.live[i]) continue;
    const std::size_t p = row_base + static_cast<std::size_t>(i);
    const std::uint32_t stencil = fb_.stencil[p];
    counters.stencil_bits_read += static_cast<std::uint64_t>(cfg.stencil_bits);
    if (!compare(ops.stencil_func, sref & smask, stencil & smask)) {
      span.live[i] = 0;
      ++counters.killed_stencil;
      ++killed;
      update(p, stencil, ops.stencil_fail);
      continue;
    }
    bool depth_pass = true;
    if (depth_on) {
      counters.depth_bits_read += static_cast<std::uint64_t>(cfg.depth_bits);
      depth_pass = compare(ops.depth_func, span.depth[i], fb_.depth[p]);
      if (depth_pass && ctl.depth_mask) {
        fb_.depth[p] = span.depth[i];
        counters.depth_bits_written += static_cast<std::uint64_t>(cfg.depth_bits);
      }
    }
    update(p, stencil, depth_pass ? ops.stencil_depth_pass : ops.stencil_depth_fail);
    if (!depth_pass) {
      span.live[i] = 0;
      ++counters.killed_depth;
      ++killed;
    }
  }
  return killed;
}

FragmentOps::Plan FragmentOps::plan() const {
  const FragmentOpsState& ops = *in_.ops;
  const FramebufferControlState& ctl = *in_.control;
  const FramebufferConfig& cfg = fb_.config;
  const std::array<int, 4>& fragment_bits = *in_.fragment_bits;
  Plan p;
  p.replace_only = use_specialised() && !ops.alpha_test && !(ops.stencil_test && cfg.stencil_bits > 0) && !ops.blend &&
                   !ops.logic_op_enabled && fragment_bits == cfg.color_bits && in_.draw_buffers->size() == 1;
  if (p.replace_only) return p;
  if (ops.alpha_test) p.alpha_ref = float_to_fixed(ops.alpha_ref, fragment_bits[3]);
  p.stencil_on = ops.stencil_test && cfg.stencil_bits > 0;
  p.depth_on = ops.depth_test && cfg.depth_bits > 0;
  p.logic_on = ops.logic_op_enabled;
  p.blend_on = ops.blend && !p.logic_on;
  for (int k = 0; k < 4; ++k)
    if (ctl.color_mask[k]) p.mask_bits += cfg.color_bits[k];
  p.total_bits = cfg.color_bits[0] + cfg.color_bits[1] + cfg.color_bits[2] + cfg.color_bits[3];
  p.same_widths = fragment_bits == cfg.color_bits;
  p.all_channels = ctl.color_mask[0] && ctl.color_mask[1] && ctl.color_mask[2] && ctl.color_mask[3];
  // The masked write (§4.2.2) keeps only these channels: the others need no blend.
  for (int k = 0; k < 4; ++k) p.written[k] = ctl.color_mask[k] && cfg.color_bits[k] > 0;
  p.unit_factors = p.blend_on && p.same_widths && use_specialised() &&
                   blend_has_unit_factors(ops.blend_equation, ops.blend_src, ops.blend_dst);
  if (p.unit_factors) {
    // Factors 0 and 1 on codes of one width: the same results in integers. A channel
    // without bits is not written, so it needs no value.
    p.unit.equation = ops.blend_equation;
    p.unit.src_one = ops.blend_src == GL_ONE;
    p.unit.dst_one = ops.blend_dst == GL_ONE;
    for (int k = 0; k < 4; ++k) {
      p.unit.max[k] = max_code(cfg.color_bits[k]);
      p.unit.written[k] = p.written[k];
    }
  } else if (p.blend_on) {
    p.real.equation = ops.blend_equation;
    p.real.src_factor = ops.blend_src;
    p.real.dst_factor = ops.blend_dst;
    p.real.products_rounded = in_.arithmetic && in_.arithmetic->blend_products_rounded;
    for (int k = 0; k < 4; ++k) {
      p.real.constant[k] = ops.blend_color[k];
      p.real.src_bits[k] = fragment_bits[k];
      p.real.dst_bits[k] = cfg.color_bits[k];
      p.real.written[k] = p.written[k];
    }
  }
  return p;
}

void FragmentOps::process(FragmentSpan& span) {
  // What depends on the state alone is found once for all the span's rows.
  const Plan p = plan();
  if (!span.rows) return process_row(p, span);
  for (int k = 0; k < span.row_count; ++k) {
    FragmentSpan row = span.row(k);
    process_row(p, row);
  }
}

void FragmentOps::process_row(const Plan& p, FragmentSpan& span) {
  const FragmentOpsState& ops = *in_.ops;
  const FramebufferControlState& ctl = *in_.control;
  const FramebufferConfig& cfg = fb_.config;
  Counters& counters = *counters_;
  const std::array<int, 4>& fragment_bits = *in_.fragment_bits;
  std::uint8_t* live = span.live;
  int begin = 0, end = span.count;

  // Scissor (§4.1.2): left <= x < left + width, bottom <= y < bottom + height.
  if (ops.scissor_enabled) {
    const bool row_in = span.y >= ops.scissor_y && span.y < ops.scissor_y + ops.scissor_height;
    const int a = row_in ? std::clamp(ops.scissor_x - span.x0, 0, span.count) : 0;
    const int b = row_in ? std::clamp(ops.scissor_x + ops.scissor_width - span.x0, a, span.count) : 0;
    counters.killed_scissor += static_cast<std::uint64_t>(span.count - (b - a));
    begin = a;
    end = b;
  }
  if (begin >= end) return;
  if (p.replace_only) {
    replace_span(span, begin, end, counters);
    return;
  }
  std::fill(live + begin, live + end, std::uint8_t{1});
  std::uint64_t alive = static_cast<std::uint64_t>(end - begin);

  // Alpha test (§4.1.3): reference and fragment alpha compared as codes at the alpha width.
  if (ops.alpha_test) {
    for (int i = begin; i < end; ++i) {
      if (!compare(ops.alpha_func, span.rgba[4 * i + 3], p.alpha_ref)) {
        live[i] = 0;
        ++counters.killed_alpha;
        --alive;
      }
    }
  }

  // Stencil (§4.1.4) and depth (§4.1.5) tests; the stencil update depends on both.
  const std::size_t row_base = fb_.pixel_index(span.x0, span.y);
  if (p.depth_on && !p.stencil_on) {
    alive -= depth_only(ops.depth_func, ctl.depth_mask, span, begin, end, fb_.depth.data() + row_base,
                        static_cast<std::int64_t>(alive), counters);
  } else if (p.stencil_on) {
    alive -= stencil_and_depth(ops, ctl, span, begin, end, row_base, p.depth_on, counters);
  }
  counters.fragments_written += alive;
  if (alive == 0) return;

  // Blending (§4.1.6), logic op (§4.1.7; it replaces blending), masked write (§4.2.2),
  // once per draw buffer.
  for (ColorBufferId id : *in_.draw_buffers) {
    std::uint16_t* dst = fb_.color[static_cast<int>(id)].rgba.data() + 4 * row_base;
    counters.color_bits_written += alive * static_cast<std::uint64_t>(p.mask_bits);
    if (!p.blend_on && !p.logic_on && p.same_widths) {
      // Replace: the fragment's codes go straight through the colour mask.
      for (int i = begin; i < end; ++i) {
        if (!live[i]) continue;
        std::uint16_t* d = dst + 4 * i;
        const std::uint16_t* src = span.rgba + 4 * i;
        if (p.all_channels) {
          std::memcpy(d, src, 4 * sizeof(std::uint16_t));
        } else {
          for (int k = 0; k < 4; ++k)
            if (ctl.color_mask[k]) d[k] = src[k];
        }
      }
      continue;
    }
    if (p.unit_factors) {
      const std::uint64_t blended = blend_span_unit_factors(p.unit, live, span.rgba, dst, begin, end);
      counters.blend_operations += blended;
      counters.color_bits_read += blended * static_cast<std::uint64_t>(p.total_bits);
      continue;
    }
    if (p.blend_on) {
      const std::uint64_t blended = !use_specialised() ? blend_span_reals_scalar(p.real, live, span.rgba, dst, begin, end)
                                                      : blend_span_reals(p.real, live, span.rgba, dst, begin, end);
      counters.blend_operations += blended;
      counters.color_bits_read += blended * static_cast<std::uint64_t>(p.total_bits);
      continue;
    }
    // Logic op (or a width change): the fragment's codes at the buffer's widths.
    for (int i = begin; i < end; ++i) {
      if (!live[i]) continue;
      std::uint16_t* d = dst + 4 * i;
      const std::uint16_t* s = span.rgba + 4 * i;
      std::uint32_t out[4];
      for (int k = 0; k < 4; ++k) out[k] = rescale_code(s[k], fragment_bits[k], cfg.color_bits[k]);
      if (p.logic_on) {
        for (int k = 0; k < 4; ++k) out[k] = logic_op(ops.logic_op, out[k], d[k], max_code(cfg.color_bits[k]));
        ++counters.logic_operations;
        counters.color_bits_read += static_cast<std::uint64_t>(p.total_bits);
      }
      for (int k = 0; k < 4; ++k)
        if (p.written[k]) d[k] = static_cast<std::uint16_t>(out[k]);
    }
  }
}

}  // namespace passim
