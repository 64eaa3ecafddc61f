// Image files through OpenImageIO: colour planes as 8-bit PNG (widths <= 8) or
// 16-bit PNG/TIFF (wider), depth as single-channel float EXR, stencil as 8-bit PNG.
// Files are written to a temporary name and renamed, so no half-written file remains.
#pragma once
#include <filesystem>
#include <string>

#include "trace_io/trace.hpp"

namespace passim {

// The file name an image gets (name + the extension its plane and widths call for).
std::string image_file_name(const CapturedImage& image, bool prefer_tiff = false);

// Writes the image into `dir`; returns the path. Throws std::runtime_error on failure.
std::filesystem::path write_image(const CapturedImage& image, const std::filesystem::path& dir, bool prefer_tiff = false);

// Writes an 8-bit RGB picture given top row first (3 bytes per pixel), as `file` (PNG by
// its extension), atomically. For figures and plots.
void write_rgb8(const std::filesystem::path& file, int width, int height, const std::vector<std::uint8_t>& top_first);

// Writes text to `path` atomically (temporary file + rename).
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace passim
