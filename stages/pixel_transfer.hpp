// Pixel transfer (OpenGL 1.2.1 §3.6.5, ARB_imaging), in the spec's order. Modelled so far:
// RGBA scale and bias, the colour matrix with its post scale and bias, depth scale and bias.
// No clamp anywhere in between (clamping happens at the final conversion).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "pipeline/counters.hpp"
#include "pipeline/state.hpp"
#include "stages/convolution.hpp"
#include "client/pixel_unpack.hpp"

namespace passim {

// A colour table (ARB_imaging §3.6.3). Entries are kept as reals after their scale, bias
// and clamp (A24: no quantisation); a LUMINANCE or INTENSITY entry is kept in [0].
struct ColorTable {
  bool enabled = false;
  GLenum internal_format = GL_RGBA;
  GLenum base = GL_RGBA;
  std::vector<Rgba> entries;  // width = entries.size()
  Vec4 scale{1.0, 1.0, 1.0, 1.0}, bias{0.0, 0.0, 0.0, 0.0};
};

enum ColorTableIndex { kColorTable = 0, kPostConvolutionTable = 1, kPostColorMatrixTable = 2 };

// HISTOGRAM and MINMAX (ARB_imaging, §3.6.5 steps 9-10).
struct Histogram {
  bool enabled = false;
  GLenum internal_format = GL_RGBA;
  GLenum base = GL_RGBA;
  bool sink = false;
  std::vector<std::array<std::uint32_t, 4>> counts;  // width entries; L counted in [0]
};
struct Minmax {
  bool enabled = false;
  GLenum internal_format = GL_RGBA;
  GLenum base = GL_RGBA;
  bool sink = false;
  Rgba min{}, max{};  // reset: min = +FLT_MAX, max = −FLT_MAX (A23)
  void reset();
};

// Table 6.17 (pixel transfer).
struct PixelTransferState {
  Vec4 scale{1.0, 1.0, 1.0, 1.0}, bias{0.0, 0.0, 0.0, 0.0};
  double depth_scale = 1.0, depth_bias = 0.0;
  bool map_color = false, map_stencil = false;
  int index_shift = 0, index_offset = 0;
  Vec4 post_color_matrix_scale{1.0, 1.0, 1.0, 1.0}, post_color_matrix_bias{0.0, 0.0, 0.0, 0.0};
  std::array<ColorTable, 3> tables{};  // COLOR_TABLE, POST_CONVOLUTION_, POST_COLOR_MATRIX_
  // Convolution: the filters and their enables; post-convolution scale and bias.
  ConvolutionFilter filter_1d, filter_2d, filter_separable;
  bool convolution_1d = false, convolution_2d = false, separable_2d = false;
  Vec4 post_convolution_scale{1.0, 1.0, 1.0, 1.0}, post_convolution_bias{0.0, 0.0, 0.0, 0.0};
  Histogram histogram;
  Minmax minmax;
  // PixelMap R_TO_R, G_TO_G, B_TO_B, A_TO_A (A19: entries clamped when given); initial {0}.
  std::array<std::vector<double>, 4> color_maps{std::vector<double>{0.0}, std::vector<double>{0.0},
                                                std::vector<double>{0.0}, std::vector<double>{0.0}};
  std::vector<std::vector<double>> other_maps = std::vector<std::vector<double>>(6, std::vector<double>{0.0});
  // Not GL state: stages the what-if study removes (passim study what-if), whatever the
  // program enables — the three colour tables, the convolution with its post scale and bias,
  // the colour matrix with its post scale and bias.
  struct Removed {
    bool color_tables = false, convolution = false, color_matrix = false;
  } removed;
};

// Which convolution an operation uses (§3.6.5): CONVOLUTION_1D for 1D textures; for 2D images
// CONVOLUTION_2D, else SEPARABLE_2D. nullptr when none is enabled.
const ConvolutionFilter* active_convolution(const PixelTransferState& state, int dims);

// §3.6.5 step 4/6/8: the components the table's base format replaces are looked up at
// round(clamp(c, 0, 1)·(W − 1)) (Table 3.13); the others pass unchanged and unclamped.
void color_table_lookup(const ColorTable& table, Rgba& c);

// The per-call constants of the per-pixel steps before the convolution (2 scale and bias,
// 3 MAP_COLOR, 4 COLOR_TABLE) and after it (6 POST_CONVOLUTION_COLOR_TABLE, 7 colour matrix
// and its scale and bias, 8 POST_COLOR_MATRIX_COLOR_TABLE), for the row kernels below.
struct TransferPlan {
  const PixelTransferState* state = nullptr;
  const Mat4* matrix = nullptr;
  bool scale_bias = false, map_color = false, color_matrix = false;
  const ColorTable* tables[3] = {};  // nullptr where the table is disabled or empty
};
TransferPlan plan_transfer(const PixelTransferState& state, const Mat4& color_matrix);

// Steps 2-4 and 6-8 over n pixels in place. The scalar functions are the reference; the
// AVX2 ones (one pixel's four components per instruction) compute the same IEEE operations
// in the same order and agree bit for bit (tests/pixel_transfer_kernels_test.cpp). The AVX2
// pre-convolution kernel does not do MAP_COLOR (the caller uses the scalar one then).
void transfer_pre_convolution_scalar(const TransferPlan& plan, Rgba* pixels, std::size_t n);
void transfer_pre_convolution_avx2(const TransferPlan& plan, Rgba* pixels, std::size_t n);
void transfer_post_convolution_scalar(const TransferPlan& plan, Rgba* pixels, std::size_t n);
void transfer_post_convolution_avx2(const TransferPlan& plan, Rgba* pixels, std::size_t n);

// The final conversion of a pixel rectangle's colours (§3.6.4, §2.13.9): clamp each
// component to [0, 1] (NaN to 0), then code = ⌊c·max_k + ½⌋; four codes per pixel.
void color_codes_from_reals_scalar(const Rgba* pixels, std::size_t n, const double max[4], std::uint16_t* out);
void color_codes_from_reals_avx2(const Rgba* pixels, std::size_t n, const double max[4], std::uint16_t* out);
void color_codes_from_reals(const Rgba* pixels, std::size_t n, const double max[4], std::uint16_t* out);

// True when steps 2–8 take each component through a function of that component alone (scale
// and bias, MAP_COLOR and the three colour tables look a component up at its own value): no
// convolution for `dims`, no colour-matrix step (plan_transfer's color_matrix), no histogram
// and no minmax. Then the result for every code of a component can be found once and looked
// up per pixel (Context::copy_pixels_through_table).
bool transfer_per_component(const PixelTransferState& state, const Mat4& color_matrix, int dims);
// Steps 2–4 and 6–8 over n pixels in place, counting nothing (with no convolution between
// them: the caller has checked transfer_per_component).
void transfer_per_pixel_steps(const PixelTransferState& state, const Mat4& color_matrix, Rgba* pixels, std::size_t n);
// The counters of a transfer of n_in pixels (n_out after a REDUCE convolution).
void count_transfer(const PixelTransferState& state, const Mat4& color_matrix, std::uint64_t n_in,
                    std::uint64_t n_out, Counters& counters);

// Applies the RGBA transfer operations to a width x height image in place, in the spec's
// order; a REDUCE convolution changes width and height. `dims` is 1 for 1D textures.
// Returns false when a histogram or minmax sink consumed the pixels (nothing further is
// drawn, returned or stored).
// `spare`: storage for the convolution's output (see convolve). `split`: runs the per-pixel
// steps and the convolution by ranges of rows as it chooses (see convolve); the histogram
// and minmax run whole, in order.
bool transfer_rgba(std::vector<Rgba>& pixels, int& width, int& height, PixelTransferState& state,
                   const Mat4& color_matrix, Counters& counters, int dims = 2, std::vector<Rgba>* spare = nullptr,
                   const RowSplitter* split = nullptr);
void transfer_depth(std::vector<double>& depth, const PixelTransferState& state);
// Stencil indices (§3.6.5 "arithmetic on indices"): shifted by INDEX_SHIFT (left when
// positive, right when negative, keeping the fraction), INDEX_OFFSET added, then with
// MAP_STENCIL replaced by PIXEL_MAP_S_TO_S[integer part mod the map's size] (fixed_point.hpp).
void transfer_stencil(std::vector<double>& indices, const PixelTransferState& state, Counters& counters);

}  // namespace passim
