// Helpers shared by the tests.
#pragma once
#include <array>
#include <cstdint>

#include <sstream>

#include "pipeline/context.hpp"
#include "trace_io/trace.hpp"

namespace passim::test {

inline FramebufferConfig small_config(int w, int h, int bits = 8) {
  FramebufferConfig c;
  c.width = w;
  c.height = h;
  c.color_bits = {bits, bits, bits, bits};
  c.depth_bits = 24;
  c.stencil_bits = 8;
  c.accum_bits = FramebufferConfig::default_accum_bits(c.color_bits);
  c.double_buffer = false;
  return c;
}

// RGBA codes of pixel (x, y) of the front buffer.
inline std::array<std::uint32_t, 4> pixel(const Context& ctx, int x, int y) {
  const Framebuffer& fb = ctx.framebuffer();
  const std::size_t p = 4 * fb.pixel_index(x, y);
  const auto& c = fb.color[0].rgba;
  return {c[p], c[p + 1], c[p + 2], c[p + 3]};
}

// Object coordinates = window coordinates; window z = (1 - z) / 2.
inline void window_projection(Context& ctx) {
  const FramebufferConfig& c = ctx.config();
  ctx.glMatrixMode(GL_PROJECTION);
  ctx.glLoadIdentity();
  ctx.glOrtho(0, c.width, 0, c.height, -1, 1);
  ctx.glMatrixMode(GL_MODELVIEW);
  ctx.glLoadIdentity();
}

// Records every call made on `ctx` from now on as a .pass trace in `text`.
struct Recording {
  explicit Recording(Context& ctx) {
    TraceSettings settings;
    settings.framebuffer = ctx.config();
    writer.write_header(settings);
    ctx.set_call_sink(&writer);
  }
  std::ostringstream text;
  TraceWriter writer{text};
};

}  // namespace passim::test
