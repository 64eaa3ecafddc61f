#include "programs/plot.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "reports/image_io.hpp"
#include "trace_io/trace.hpp"

namespace passim {
namespace {

constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

// Distinguishable line colours (Okabe–Ito).
const float kColours[][3] = {{0.00f, 0.45f, 0.70f}, {0.84f, 0.37f, 0.00f}, {0.00f, 0.62f, 0.45f},
                             {0.80f, 0.47f, 0.65f}, {0.94f, 0.89f, 0.26f}, {0.34f, 0.71f, 0.91f},
                             {0.90f, 0.62f, 0.00f}, {0.00f, 0.00f, 0.00f}};

// A "nice" step for about `count` ticks over [lo, hi].
double tick_step(double lo, double hi, int count) {
  const double raw = (hi - lo) / count;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * mag) return m * mag;
  return 10.0 * mag;
}

}  // namespace

namespace {

// An 8-bit RGB image buffer out through the project's atomic image writer.
void write_buffer(const std::filesystem::path& file, const OIIO::ImageBuf& buf) {
  const int width = buf.spec().width, height = buf.spec().height;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  buf.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8, pixels.data());
  write_rgb8(file, width, height, pixels);
}

}  // namespace

void write_strip(const std::filesystem::path& file, const std::vector<std::filesystem::path>& images,
                 const std::vector<std::string>& labels) {
  using namespace OIIO;
  std::vector<ImageBuf> cells;
  int width = 0, height = 0;
  ImageSpec config;  // the files' colour as stored, not multiplied by alpha
  config.attribute("oiio:UnassociatedAlpha", 1);
  for (const auto& path : images) {
    ImageBuf b(path.string(), 0, 0, nullptr, &config);
    if (!b.read(0, 0, 0, 3, true, TypeDesc::UINT8))
      throw std::runtime_error(fmt::format("cannot read {}: {}", path.string(), b.geterror()));
    width += b.spec().width + (cells.empty() ? 0 : 4);
    height = std::max(height, b.spec().height);
    cells.push_back(std::move(b));
  }
  ImageBuf strip(ImageSpec(std::max(1, width), height + 24, 3, TypeDesc::UINT8));
  ImageBufAlgo::fill(strip, {1.0f, 1.0f, 1.0f});
  int x = 0;
  bool text_ok = true;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    ImageBufAlgo::paste(strip, x, 0, 0, 0, cells[k]);
    if (text_ok && k < labels.size())
      text_ok = ImageBufAlgo::render_text(strip, x + 4, height + 18, labels[k], 14, kFont, {0.1f, 0.1f, 0.1f});
    x += cells[k].spec().width + 4;
  }
  write_buffer(file, strip);
}

void write_plot(const std::filesystem::path& file, const PlotSpec& plot, int width, int height) {
  // Room on the right for the legend.
  using namespace OIIO;
  ImageBuf buf(ImageSpec(width, height, 3, TypeDesc::UINT8));
  ImageBufAlgo::fill(buf, {1.0f, 1.0f, 1.0f});
  bool text_ok = true;
  auto text = [&](int x, int y, const std::string& s, int size, bool centred = false) {
    if (!text_ok) return;
    ROI box = ImageBufAlgo::text_size(s, size, kFont);
    const int dx = centred && box.defined() ? -box.width() / 2 : 0;
    text_ok = ImageBufAlgo::render_text(buf, x + dx, y, s, size, kFont, {0.1f, 0.1f, 0.1f});
  };
  const int left = 80, right = width - 230, top = 52, bottom = height - 60;
  // Data range.
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  auto fy = [&](double y) { return plot.log_y ? std::log10(y) : y; };
  for (const PlotSeries& s : plot.series)
    for (std::size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
      if (plot.log_y && !(s.y[k] > 0.0)) continue;
      x0 = std::min(x0, s.x[k]), x1 = std::max(x1, s.x[k]);
      y0 = std::min(y0, fy(s.y[k])), y1 = std::max(y1, fy(s.y[k]));
    }
  if (!std::isfinite(x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (x1 == x0) x0 -= 1, x1 += 1;
  if (y1 == y0) y0 -= 1, y1 += 1;
  if (!plot.log_y && y0 > 0 && y0 < 0.5 * y1) y0 = 0;
  const double ypad = 0.05 * (y1 - y0);
  y0 -= ypad, y1 += ypad;
  auto px = [&](double x) { return left + static_cast<int>(std::lround((x - x0) / (x1 - x0) * (right - left))); };
  auto py = [&](double y) { return bottom - static_cast<int>(std::lround((y - y0) / (y1 - y0) * (bottom - top))); };
  // Axes, ticks and grid.
  const float grey[3] = {0.85f, 0.85f, 0.85f}, black[3] = {0.2f, 0.2f, 0.2f};
  const double xs = tick_step(x0, x1, 8);
  for (double x = std::ceil(x0 / xs) * xs; x <= x1 + 1e-9; x += xs) {
    ImageBufAlgo::render_line(buf, px(x), top, px(x), bottom, grey);
    text(px(x), bottom + 18, fmt::format("{:g}", x), 13, true);
  }
  std::vector<double> y_ticks;  // in plotted units (log10 on a log axis)
  if (plot.log_y) {
    // 1, 2, 5 times each decade; every integer multiple when that gives fewer than two.
    for (const std::vector<double>& ms : {std::vector<double>{1, 2, 5}, std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9}}) {
      y_ticks.clear();
      for (int e = static_cast<int>(std::floor(y0)); e <= static_cast<int>(std::ceil(y1)); ++e)
        for (double m : ms) {
          const double t = std::log10(m) + e;
          if (t >= y0 && t <= y1) y_ticks.push_back(t);
        }
      if (y_ticks.size() >= 2) break;
    }
  } else {
    const double ys = tick_step(y0, y1, 6);
    for (double y = std::ceil(y0 / ys) * ys; y <= y1 + 1e-9; y += ys) y_ticks.push_back(y);
  }
  for (double y : y_ticks) {
    ImageBufAlgo::render_line(buf, left, py(y), right, py(y), grey);
    text(8, py(y) + 5, plot.log_y ? fmt::format("{:.3g}", std::pow(10.0, y)) : fmt::format("{:.6g}", y), 13);
  }
  ImageBufAlgo::render_line(buf, left, bottom, right, bottom, black);
  ImageBufAlgo::render_line(buf, left, top, left, bottom, black);
  // Series: lines and square markers.
  for (std::size_t s = 0; s < plot.series.size(); ++s) {
    const float* c = kColours[s % std::size(kColours)];
    const PlotSeries& ser = plot.series[s];
    int last_x = 0, last_y = 0;
    bool have_last = false;
    for (std::size_t k = 0; k < ser.x.size() && k < ser.y.size(); ++k) {
      if (plot.log_y && !(ser.y[k] > 0.0)) {
        have_last = false;
        continue;
      }
      const int X = px(ser.x[k]), Y = py(fy(ser.y[k]));
      if (have_last) ImageBufAlgo::render_line(buf, last_x, last_y, X, Y, {c[0], c[1], c[2]});
      ImageBufAlgo::render_box(buf, X - 3, Y - 3, X + 3, Y + 3, {c[0], c[1], c[2]}, true);
      last_x = X, last_y = Y, have_last = true;
    }
    ImageBufAlgo::render_box(buf, right + 15, top + 10 + 22 * static_cast<int>(s) - 5, right + 25,
                             top + 10 + 22 * static_cast<int>(s) + 5, {c[0], c[1], c[2]}, true);
    text(right + 32, top + 15 + 22 * static_cast<int>(s), ser.name, 13);
  }
  text((left + right) / 2, 22, plot.title, 16, true);
  text((left + right) / 2, height - 15, plot.x_label, 14, true);
  text(8, top - 10, plot.y_label, 14);
  write_buffer(file, buf);
}

}  // namespace passim
