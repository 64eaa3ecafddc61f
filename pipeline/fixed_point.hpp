// Fixed-point conversions of OpenGL 1.2.1 §2.13.9 with the tie rule of
// docs/arithmetic.md (A1: round to nearest, ties up: floor(x + 0.5)).
#pragma once
#include <cmath>
#include <cstdint>

namespace passim {

// 2^bits - 1 for bits in [0, 32].
constexpr std::uint32_t max_code(int bits) {
  return bits >= 32 ? 0xFFFFFFFFu : static_cast<std::uint32_t>((std::uint64_t{1} << bits) - 1);
}

// Clamp to [lo, hi]; NaN becomes lo so that no NaN ever reaches an integer conversion.
constexpr double clamp_nan_low(double v, double lo, double hi) {
  if (!(v > lo)) return lo;  // also catches NaN
  if (v > hi) return hi;
  return v;
}

// floor(x) without a library call where the value fits an integer; the same result as
// std::floor for every double (both are exact).
inline double floor_exact(double x) {
  if (!(x > -4.0e15 && x < 4.0e15)) return std::floor(x);
  const double t = static_cast<double>(static_cast<long long>(x));
  return t > x ? t - 1.0 : t;
}

// A1: round to nearest, ties towards +infinity.
inline double round_half_up(double x) { return floor_exact(x + 0.5); }

// §2.13.9: k = round(clamp(c, 0, 1) * (2^bits - 1)).
inline std::uint32_t float_to_fixed(double c, int bits) {
  const double m = static_cast<double>(max_code(bits));
  // The argument is >= 0.5, so truncation is floor(x + 0.5) exactly, without a libm call.
  return static_cast<std::uint32_t>(clamp_nan_low(c, 0.0, 1.0) * m + 0.5);
}

// §2.13.9: c = k / (2^bits - 1); 0 and 1 are exact. A 0-bit channel reads as 1 (absent alpha).
inline double fixed_to_float(std::uint32_t k, int bits) {
  if (bits == 0) return 1.0;
  return static_cast<double>(k) / static_cast<double>(max_code(bits));
}

// fixed_to_float through a table built once per width (1-16 bits): the same values,
// without a division per call.
const double* code_values(int bits);
inline double code_value(std::uint32_t k, int bits) {
  if (bits == 0) return 1.0;
  return code_values(bits)[k];
}

// Quantise a real colour to the nearest representable value at `bits`.
inline double quantise(double c, int bits) {
  if (bits == 0) return 1.0;
  return fixed_to_float(float_to_fixed(c, bits), bits);
}

// Indices (§3.6.5 "arithmetic on indices", §4.3.1, Table 4.6) are fixed-point values kept as
// doubles (exact for every integer index and every fraction a FLOAT index or a right shift
// makes); their integer part is the floor (two's complement) and "ANDed with 2^b − 1" is
// that integer modulo 2^b. A NaN or infinite index has no integer part: 0 (A27).
inline std::uint64_t index_low_bits(double index, int bits) {
  if (!std::isfinite(index)) return 0;
  const double modulus = std::ldexp(1.0, bits);
  double m = std::fmod(std::floor(index), modulus);  // exact
  if (m < 0.0) m += modulus;
  return static_cast<std::uint64_t>(m);
}

// Re-express a code at `from` bits at `to` bits (A2: round(u * (2^to-1)/(2^from-1))).
inline std::uint32_t rescale_code(std::uint32_t k, int from, int to) {
  if (from == to) return k;
  return float_to_fixed(fixed_to_float(k, from), to);
}

}  // namespace passim
