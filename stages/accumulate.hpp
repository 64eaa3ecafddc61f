// The accumulation buffer, OpenGL 1.2.1 §4.2.4, with the fixed point of A21: signed
// codes at the plane's width A, scale 2^(A−1) − 1, every result rounded (A1) and
// saturated to [−1, 1] (overflow is undefined in the spec). RETURN writes
// clamp(value·acc, 0, 1) to the draw buffers through the colour mask and scissor only.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/framebuffer.hpp"
#include "pipeline/state.hpp"

namespace passim {

// op is GL_ACCUM, GL_LOAD, GL_ADD, GL_MULT or GL_RETURN (validated by the caller).
void accumulate(GLenum op, double value, const PixelBox& region, const ColorPlane& read,
                const std::vector<ColorBufferId>& draw, const std::array<bool, 4>& color_mask, Framebuffer& fb,
                Counters& counters);

// One operation over a row of pixels. The scalar functions are the reference; the AVX2
// ones compute the same IEEE operations in the same order (one pixel's four components
// per instruction), so the two agree bit for bit (tests/accumulation_test.cpp).
struct AccumRowOp {
  GLenum op = GL_ACCUM;
  double value = 0.0;
  double scale = 0.0;                // 2^(A−1) − 1
  const double* term[4] = {};        // ACCUM, LOAD: value·c of each read code, indexed by code & code_mask
  std::uint32_t code_mask[4] = {};   // 0 for an absent channel (read as 1, A21)
  double color_max[4] = {};          // RETURN: 2^bits − 1 of each colour channel
};
// ACCUM, LOAD, ADD, MULT: n pixels' four accumulation codes in place; `read` holds the
// read buffer's four codes per pixel (ACCUM and LOAD only).
void accumulate_row_scalar(const AccumRowOp& op, std::int32_t* acc, const std::uint16_t* read, int n);
void accumulate_row_avx2(const AccumRowOp& op, std::int32_t* acc, const std::uint16_t* read, int n);
// RETURN: the four colour codes of n pixels, before the colour mask.
void return_row_scalar(const AccumRowOp& op, const std::int32_t* acc, std::uint16_t* out, int n);
void return_row_avx2(const AccumRowOp& op, const std::int32_t* acc, std::uint16_t* out, int n);

}  // namespace passim
