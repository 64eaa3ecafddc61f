#include "client/glu_mipmaps.hpp"

#include <cstdint>
#include <cstring>

namespace passim {

namespace {

// One output element from the inputs of its box (4) or pair (2), per GLU 1.3's halveImage.
double halve_elements(const double* v, int count, GLenum type) {
  switch (type) {
    case GL_UNSIGNED_BYTE:
    case GL_BYTE:
    case GL_UNSIGNED_SHORT:
    case GL_SHORT: {
      // C int arithmetic: the sum (+ 2 for the box) divided, truncating toward zero.
      std::int64_t sum = 0;
      for (int k = 0; k < count; ++k) sum += static_cast<std::int64_t>(v[k]);
      return static_cast<double>(count == 4 ? (sum + 2) / 4 : sum / 2);
    }
    case GL_UNSIGNED_INT: {
      const double r = count == 4 ? (v[0] + v[1] + v[2] + v[3]) / 4 + 0.5 : (v[0] + v[1]) / 2.0;
      return static_cast<double>(static_cast<std::uint32_t>(r));
    }
    case GL_INT: {
      if (count == 4) {
        const float sum = static_cast<float>(v[0]) + static_cast<float>(v[1]) + static_cast<float>(v[2]) +
                          static_cast<float>(v[3]);
        return static_cast<double>(static_cast<std::int32_t>(static_cast<double>(sum / 4) + 0.5));
      }
      // The pair reads its ints as unsigned (GLuint), sums in float, divides in double.
      const float a = static_cast<float>(static_cast<std::uint32_t>(static_cast<std::int32_t>(v[0])));
      const float b = static_cast<float>(static_cast<std::uint32_t>(static_cast<std::int32_t>(v[1])));
      const double r = static_cast<double>(a + b) / 2.0;
      // Converting an out-of-range value is undefined in C; x86 gives INT_MIN, kept here.
      return r >= 2147483648.0 ? -2147483648.0 : static_cast<double>(static_cast<std::int32_t>(r));
    }
    default: {  // GL_FLOAT
      if (count == 4) {
        const float sum = static_cast<float>(v[0]) + static_cast<float>(v[1]) + static_cast<float>(v[2]) +
                          static_cast<float>(v[3]);
        return static_cast<double>(sum / 4);
      }
      return static_cast<double>(static_cast<float>(static_cast<double>(static_cast<float>(v[0]) + static_cast<float>(v[1])) / 2.0));
    }
  }
}

}  // namespace

std::vector<double> glu_halve_image(const std::vector<double>& image, int width, int height, int components,
                                    GLenum type) {
  const int w = width > 1 ? width / 2 : 1, h = height > 1 ? height / 2 : 1;
  const std::size_t n = static_cast<std::size_t>(components);
  std::vector<double> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * n);
  auto at = [&](int x, int y, std::size_t c) {
    return image[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * n + c];
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (std::size_t c = 0; c < n; ++c) {
        double v[4];
        int count;
        if (width > 1 && height > 1) {
          v[0] = at(2 * x, 2 * y, c), v[1] = at(2 * x + 1, 2 * y, c);
          v[2] = at(2 * x, 2 * y + 1, c), v[3] = at(2 * x + 1, 2 * y + 1, c);
          count = 4;
        } else if (width > 1) {
          v[0] = at(2 * x, 0, c), v[1] = at(2 * x + 1, 0, c);
          count = 2;
        } else {
          v[0] = at(0, 2 * y, c), v[1] = at(0, 2 * y + 1, c);
          count = 2;
        }
        out[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) * n + c] =
            halve_elements(v, count, type);
      }
  return out;
}

std::vector<std::byte> pack_elements(const std::vector<double>& elements, GLenum type) {
  std::vector<std::byte> out;
  auto put = [&out](auto value) {
    const std::size_t at = out.size();
    out.resize(at + sizeof(value));
    std::memcpy(out.data() + at, &value, sizeof(value));
  };
  for (double e : elements) {
    switch (type) {
      case GL_UNSIGNED_BYTE: put(static_cast<std::uint8_t>(e)); break;
      case GL_BYTE: put(static_cast<std::int8_t>(e)); break;
      case GL_UNSIGNED_SHORT: put(static_cast<std::uint16_t>(e)); break;
      case GL_SHORT: put(static_cast<std::int16_t>(e)); break;
      case GL_UNSIGNED_INT: put(static_cast<std::uint32_t>(e)); break;
      case GL_INT: put(static_cast<std::int32_t>(e)); break;
      default: put(static_cast<float>(e)); break;
    }
  }
  return out;
}

}  // namespace passim
