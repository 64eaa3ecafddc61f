// Convolution (ARB_imaging; OpenGL 1.2.1 §3.6.3, §3.6.5 step 5): 1D, 2D and separable
// filters, border modes REDUCE (smaller output, anchored at the source's lower left),
// CONSTANT_BORDER and REPLICATE_BORDER (same size, centred on ⌊Wf/2⌋, ⌊Hf/2⌋); the filter's
// base format chooses the convolved components (Table 3.14). No clamping.
#pragma once
#include <functional>
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/state.hpp"
#include "client/pixel_unpack.hpp"
#include "stages/row_splitter.hpp"

namespace passim {

struct ConvolutionFilter {
  GLenum internal_format = GL_RGBA;
  GLenum base = GL_RGBA;
  int width = 0, height = 0;   // height 1 for 1D
  std::vector<Rgba> taps;      // width x height, rows bottom first; separable: row x column product
  std::vector<Rgba> row, column;  // separable filters only
  bool separable = false;
  Vec4 scale{1.0, 1.0, 1.0, 1.0}, bias{0.0, 0.0, 0.0, 0.0};  // FILTER_SCALE, FILTER_BIAS
  GLenum border_mode = GL_REDUCE;
  Vec4 border_color{0.0, 0.0, 0.0, 0.0};
  // The tap (n, m), n left to right, m bottom to top.
  Rgba tap(int n, int m) const;
};

// Convolves a width x height image in place; width and height become the output size
// (smaller under REDUCE, possibly 0). `Scalar` computes every pixel with the reference
// loop; `Fastest` computes the pixels whose footprint lies inside the image with an AVX2
// kernel (when the processor has it) that performs the same IEEE operations in the same
// order — the results are the same bits (tests/pixel_transfer_kernels_test.cpp).
// `spare`, when given, is storage the output is built in and the input's storage is
// handed back in (a caller that convolves often keeps its allocation).
// `split`, when given, runs the output rows' work as it chooses (on several threads; every
// output row is computed alone from the input).
enum class ConvolutionKernel { Scalar, Fastest };
void convolve(std::vector<Rgba>& image, int& width, int& height, const ConvolutionFilter& filter, Counters& counters,
              ConvolutionKernel kernel = ConvolutionKernel::Fastest, std::vector<Rgba>* spare = nullptr,
              const RowSplitter* split = nullptr);

// The fast path's view of a convolution (convolution_fast.cpp): the taps as each output
// component reads them (tap[n + m·wf][k] is the filter component that component k is multiplied
// by), and which components the filter convolves.
struct InteriorRows {
  const Rgba* image;
  int ws, wf, hf, cw, ch;
  const Rgba* taps;
  bool conv[4];
  Rgba* out;
  int wo;
};
// Output pixels (i, j), i in [i0, i1), of row j whose whole footprint lies inside the image, by
// the AVX2 kernel (where the processor has it): the reference's sum in its order.
void convolve_interior_avx2(const InteriorRows& rows, int j, int i0, int i1);

}  // namespace passim
