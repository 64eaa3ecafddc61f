// The rasterizer's per-fragment arithmetic over one span: a plain scalar reference
// (span_kernels.cpp) and SSE2 and AVX2 kernels that compute the same IEEE operations in the same
// order (span_kernels_fast.cpp), so they agree bit for bit (tests/span_kernels_test.cpp checks
// them on random input). The unsuffixed functions choose (stages/kernel_paths.hpp).
#pragma once
#include <cstdint>

namespace passim {

// A plane evaluated along a span: value(i) = (row + d_dx·dx_i), dx_i = (x0 + i + 1/2) − x_ref.
struct SpanPlane {
  double row = 0.0;
  double d_dx = 0.0;
};

// Depth codes: code(i) = round(clamp((row + d_dx·dx_i) + offset, 0, 1)·scale), scale = 2^N − 1.
void depth_codes_scalar(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                        std::uint32_t* out);
void depth_codes(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale, std::uint32_t* out);

// Perspective-correct RGBA codes: c_k(i) = round(clamp((row_k + d_dx_k·dx_i)·(1/(q.row + q.d_dx·dx_i)), 0, 1)·scale_k),
// written interleaved (4 per fragment). Scales must be below 2^16.
void color_codes_scalar(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                        std::uint16_t* out);
void color_codes(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                 std::uint16_t* out);

// Projective texture coordinates (eq. 3.4 with the planes of s/w, t/w, r/w, q/w):
// s(i) = (s.row + s.d_dx·dx_i) / (q.row + q.d_dx·dx_i), likewise t and r; plane k of `stq` is
// s, t, r, q. Only the first `used` of s, t, r (1 to 3) are computed, those the texture
// stage reads; the others are written 0. The AVX2 kernel, when the processor has it, divides four fragments at a time.
void texture_coordinates_scalar(const SpanPlane stq[4], int x0, double x_ref, int n, int used, double* s, double* t,
                                double* r);
void texture_coordinates(const SpanPlane stq[4], int x0, double x_ref, int n, int used, double* s, double* t,
                         double* r);

// The same for a caller whose buffers have room for n rounded up to a multiple of 4
// (out[n .. n+3] may be written with values of the pixels past the span): no scalar tail.
inline constexpr int kSpanPadding = 4;
void depth_codes_padded(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                        std::uint32_t* out);
void color_codes_padded(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                        std::uint16_t* out);

// The AVX2 kernel (four fragments at a time) used by color_codes when the processor has
// AVX2; exposed so the tests can compare it with the scalar reference directly.
bool color_codes_has_avx2();
bool depth_codes_has_avx2();
void depth_codes_wide(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                      std::uint32_t* out);
void color_codes_wide(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                      std::uint16_t* out);

}  // namespace passim
