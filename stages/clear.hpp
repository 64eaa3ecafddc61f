// glClear, OpenGL 1.2.1 §4.2.3: only pixel ownership, the scissor test, dithering
// (a no-op, A3) and the write masks apply.
#pragma once
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/framebuffer.hpp"
#include "pipeline/state.hpp"
#include "stages/row_splitter.hpp"

namespace passim {

// The accumulation code of a value in [-1, 1] at `bits` (A21: scale 2^(bits-1) - 1).
std::int32_t accum_code(double value, int bits);

// `split`, when given, runs the rows as it chooses (each row is cleared alone).
void clear_buffers(GLbitfield mask, const FramebufferControlState& control, const FragmentOpsState& ops,
                   const std::vector<ColorBufferId>& draw_buffers, Framebuffer& fb, Counters& counters,
                   const RowSplitter* split = nullptr);

}  // namespace passim
