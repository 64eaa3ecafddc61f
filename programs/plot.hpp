// Line charts as PNG (OpenImageIO's line and text rendering), for the studies' plots.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace passim {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;
};

struct PlotSpec {
  std::string title, x_label, y_label;
  bool log_y = false;  // logarithmic y axis (values <= 0 are left out)
  std::vector<PlotSeries> series;
};

// Writes an 8-bit RGB PNG (temporary file + rename). Labels need the DejaVu font
// (Debian's fonts-dejavu-core); without it the chart is drawn unlabelled.
void write_plot(const std::filesystem::path& file, const PlotSpec& plot, int width = 800, int height = 440);

// Joins PNG images side by side (4 pixels apart, tops aligned), each labelled below,
// into one 8-bit RGB PNG. Throws std::runtime_error when an image cannot be read.
void write_strip(const std::filesystem::path& file, const std::vector<std::filesystem::path>& images,
                 const std::vector<std::string>& labels);

}  // namespace passim
