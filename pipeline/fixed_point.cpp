#include "pipeline/fixed_point.hpp"

#include <array>
#include <vector>

namespace passim {

const double* code_values(int bits) {
  // Tables for 1..16 bits, each k / (2^bits − 1), built once (about 1 MiB in all).
  struct Tables {
    std::array<std::vector<double>, 17> values;
    Tables() {
      for (int b = 1; b <= 16; ++b) {
        values[static_cast<std::size_t>(b)].resize(static_cast<std::size_t>(max_code(b)) + 1);
        for (std::uint32_t k = 0; k <= max_code(b); ++k) values[static_cast<std::size_t>(b)][k] = fixed_to_float(k, b);
      }
    }
  };
  static const Tables tables;
  return tables.values[static_cast<std::size_t>(bits)].data();
}

}  // namespace passim
