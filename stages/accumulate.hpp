// The accumulation buffer, OpenGL 1.2.1 §4.2.4, with the fixed point of A21: signed
// codes at the plane's width A, scale 2^(A−1) − 1, every result rounded (A1) and
// saturated to [−1, 1] (overflow is undefined in the spec). RETURN writes
// clamp(value·acc, 0, 1) to the draw buffers through the colour mask and scissor only.
#pragma once
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/framebuffer.hpp"
#include "pipeline/state.hpp"

namespace passim {

struct AccumRegion {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
};

// op is GL_ACCUM, GL_LOAD, GL_ADD, GL_MULT or GL_RETURN (validated by the caller).
void accumulate(GLenum op, double value, const AccumRegion& region, const ColorPlane& read,
                const std::vector<ColorBufferId>& draw, const std::array<bool, 4>& color_mask, Framebuffer& fb,
                Counters& counters);

}  // namespace passim
