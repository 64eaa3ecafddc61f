#include "programs/figure.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "pipeline/fixed_point.hpp"
#include "reports/image_io.hpp"

namespace passim {

void write_figure(const std::filesystem::path& file, const std::vector<std::vector<FigureColumn>>& rows,
                  const InsetRegion& inset, int scale_down) {
  if (rows.empty() || rows.front().empty() || !rows.front().front().image)
    throw std::invalid_argument("write_figure: no images");
  const CapturedImage& first = *rows.front().front().image;
  const int cell_w = first.width / scale_down, cell_h = first.height / scale_down;
  const int mag = std::max(1, cell_w / inset.width);
  const int inset_h = inset.height * mag, gap = 4;
  std::size_t columns = 0;
  for (const auto& r : rows) columns = std::max(columns, r.size());
  const int fig_w = static_cast<int>(columns) * (cell_w + gap) - gap;
  const int fig_h = static_cast<int>(rows.size()) * (cell_h + inset_h + 2 * gap) - gap;
  // The canvas, top row first, 8 bits per channel, white between the cells.
  std::vector<std::array<std::uint8_t, 3>> canvas(static_cast<std::size_t>(fig_w) * static_cast<std::size_t>(fig_h),
                                                  {255, 255, 255});
  auto put = [&](int x, int y, std::array<std::uint8_t, 3> c) {
    if (x >= 0 && x < fig_w && y >= 0 && y < fig_h) canvas[static_cast<std::size_t>(y) * static_cast<std::size_t>(fig_w) + static_cast<std::size_t>(x)] = c;
  };
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      const CapturedImage& img = *rows[r][c].image;
      if (img.width != first.width || img.height != first.height || img.channels < 3)
        throw std::invalid_argument("write_figure: images of different sizes or without colour");
      // Colour of window pixel (x, y) (row 0 at the bottom) at 8 bits.
      auto pixel = [&](int x, int y) {
        std::array<std::uint8_t, 3> out{};
        const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(img.width) + static_cast<std::size_t>(x)) *
                              static_cast<std::size_t>(img.channels);
        for (int k = 0; k < 3; ++k)
          out[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(rescale_code(img.codes[i + static_cast<std::size_t>(k)], img.bits[static_cast<std::size_t>(k)], 8));
        return out;
      };
      const int x0 = static_cast<int>(c) * (cell_w + gap);
      const int y0 = static_cast<int>(r) * (cell_h + inset_h + 2 * gap);
      // The full image, box-filtered down by scale_down.
      for (int y = 0; y < cell_h; ++y)
        for (int x = 0; x < cell_w; ++x) {
          std::array<int, 3> sum{};
          for (int dy = 0; dy < scale_down; ++dy)
            for (int dx = 0; dx < scale_down; ++dx) {
              const auto p = pixel(x * scale_down + dx, img.height - 1 - (y * scale_down + dy));
              for (int k = 0; k < 3; ++k) sum[static_cast<std::size_t>(k)] += p[static_cast<std::size_t>(k)];
            }
          const int n = scale_down * scale_down;
          put(x0 + x, y0 + y,
              {static_cast<std::uint8_t>((sum[0] + n / 2) / n), static_cast<std::uint8_t>((sum[1] + n / 2) / n),
               static_cast<std::uint8_t>((sum[2] + n / 2) / n)});
        }
      // The inset's outline (Figure 7's red rectangle).
      const int left = inset.x / scale_down, right = (inset.x + inset.width) / scale_down;
      const int top = (img.height - inset.y - inset.height) / scale_down, bottom = (img.height - inset.y) / scale_down;
      for (int x = left; x <= right; ++x) put(x0 + x, y0 + top, {255, 0, 0}), put(x0 + x, y0 + bottom, {255, 0, 0});
      for (int y = top; y <= bottom; ++y) put(x0 + left, y0 + y, {255, 0, 0}), put(x0 + right, y0 + y, {255, 0, 0});
      // The inset, magnified without filtering so each pixel stays visible.
      for (int y = 0; y < inset_h; ++y)
        for (int x = 0; x < inset.width * mag; ++x)
          put(x0 + x, y0 + cell_h + gap + y, pixel(inset.x + x / mag, inset.y + inset.height - 1 - y / mag));
    }
  std::vector<std::uint8_t> bytes(canvas.size() * 3);
  for (std::size_t p = 0; p < canvas.size(); ++p)
    for (std::size_t k = 0; k < 3; ++k) bytes[3 * p + k] = canvas[p][k];
  write_rgb8(file, fig_w, fig_h, bytes);
}

}  // namespace passim
