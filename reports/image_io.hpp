// Image files: colour planes as 8-bit PNG (widths <= 8) or 16-bit PNG/TIFF (wider), depth as
// single-channel float EXR, stencil as 8-bit PNG. Each file records the planes' true widths
// (PNG sBIT and text chunks, TIFF and EXR attributes; docs/images.md). PNG through
// libpng (OpenImageIO 2.4 writes no sBIT), TIFF and EXR through OpenImageIO.
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

// Writes text to `path` atomically (temporary file + rename).
void write_text_file(const std::filesystem::path& path, const std::string& text);

}  // namespace passim
