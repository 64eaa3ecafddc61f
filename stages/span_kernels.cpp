#include "stages/span_kernels.hpp"


namespace passim {
namespace {

inline double centre_offset(int x, double x_ref) { return (static_cast<double>(x) + 0.5) - x_ref; }

// clamp to [0, 1] with NaN -> 0, then round half up (the argument is >= 0.5: truncation is floor).
inline std::uint32_t code(double v, double scale) {
  v = v > 0.0 ? v : 0.0;
  v = v < 1.0 ? v : 1.0;
  return static_cast<std::uint32_t>(v * scale + 0.5);
}

}  // namespace

void depth_codes_scalar(const SpanPlane& z, double offset, int x0, double x_ref, int n, double scale,
                        std::uint32_t* out) {
  for (int i = 0; i < n; ++i) out[i] = code((z.row + z.d_dx * centre_offset(x0 + i, x_ref)) + offset, scale);
}

void color_codes_scalar(const SpanPlane& q, const SpanPlane c[4], const double scale[4], int x0, double x_ref, int n,
                        std::uint16_t* out) {
  for (int i = 0; i < n; ++i) {
    const double dx = centre_offset(x0 + i, x_ref);
    const double inv_q = 1.0 / (q.row + q.d_dx * dx);
    for (int k = 0; k < 4; ++k)
      out[4 * i + k] = static_cast<std::uint16_t>(code((c[k].row + c[k].d_dx * dx) * inv_q, scale[k]));
  }
}

void texture_coordinates_scalar(const SpanPlane stq[4], int x0, double x_ref, int n, int used, double* s, double* t,
                                double* r) {
  double* out[3] = {s, t, r};
  for (int i = 0; i < n; ++i) {
    const double dx = centre_offset(x0 + i, x_ref);
    const double q = stq[3].row + stq[3].d_dx * dx;
    for (int k = 0; k < 3; ++k) out[k][i] = k < used ? (stq[k].row + stq[k].d_dx * dx) / q : 0.0;
  }
}

}  // namespace passim
