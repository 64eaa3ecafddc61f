#include "reports/image_io.hpp"

#include <OpenImageIO/imageio.h>
#include <png.h>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "pipeline/fixed_point.hpp"

namespace passim {
namespace {

std::filesystem::path temp_path_for(const std::filesystem::path& path) {
  // Same directory (so rename is atomic) and same extension (OpenImageIO picks the format by it).
  return path.parent_path() / (".tmp-" + path.filename().string());
}

void commit(const std::filesystem::path& tmp, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), ec.message()));
  }
}

}  // namespace

std::string image_file_name(const CapturedImage& image, bool prefer_tiff) {
  if (image.plane == "depth") return image.name + ".exr";
  if (image.plane == "stencil") return image.name + ".png";
  const int widest = *std::max_element(image.bits.begin(), image.bits.end());
  if (widest > 8 && prefer_tiff) return image.name + ".tif";
  return image.name + ".png";
}

namespace {

// How a reader gets the codes back from a file: the widths, and what a sample holds.
std::string width_note(const CapturedImage& image, int channels, int file_bits) {
  if (image.plane == "depth")
    return fmt::format("passim: depth at {} bits; each value is code / (2^{} - 1) as a 32-bit float (code = "
                       "round(value * (2^{} - 1)), exact up to 24 bits; a 32-bit float keeps 24 of a wider code's)",
                       image.bits[0], image.bits[0], image.bits[0]);
  if (image.plane == "stencil") return fmt::format("passim: stencil values at {} bits, as they are", image.bits[0]);
  std::string widths;
  for (int c = 0; c < channels; ++c) widths += fmt::format("{}{}", c ? "," : "", image.bits[static_cast<std::size_t>(c)]);
  const int widest = *std::max_element(image.bits.begin(), image.bits.begin() + channels);
  return fmt::format("passim: {}-bit codes (channels {}) in {}-bit samples; code = sample >> {} (PNG sBIT)", widest,
                     widths, file_bits, file_bits - widest);
}

// A PNG through libpng, with an sBIT chunk giving each channel's true width and the widths in
// text chunks ("passim:bits", "Description"), so that readers recover the codes
// (docs/images.md). Only C between setjmp and the end: libpng reports errors by
// longjmp. False, with the message in `error`, when the file cannot be written.
struct PngSpec {
  int width = 0, height = 0, channels = 0, depth = 8;  // depth: 8 or 16 bits per sample
  png_color_8 significant{};                         // sBIT; all zero: none
  png_text* text = nullptr;
  int text_count = 0;
  const unsigned char* rows = nullptr;  // top row first; 16-bit samples in host order
};

void png_error_to_buffer(png_structp png, png_const_charp message) {
  auto* error = static_cast<char*>(png_get_error_ptr(png));
  std::snprintf(error, 256, "%s", message);
  png_longjmp(png, 1);
}

void png_ignore_warning(png_structp, png_const_charp) {}

bool write_png(const char* path, const PngSpec& spec, char* error) {
  FILE* file = std::fopen(path, "wb");
  if (!file) {
    std::snprintf(error, 256, "%s", std::strerror(errno));
    return false;
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, png_error_to_buffer, png_ignore_warning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info) {
    std::snprintf(error, 256, "out of memory");
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    return false;
  }
  png_init_io(png, file);
  const int types[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB, PNG_COLOR_TYPE_RGB_ALPHA};
  png_set_IHDR(png, info, static_cast<png_uint_32>(spec.width), static_cast<png_uint_32>(spec.height), spec.depth,
               types[spec.channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_color_8 sbit = spec.significant;
  if (sbit.red || sbit.gray) png_set_sBIT(png, info, &sbit);
  if (spec.text_count > 0) png_set_text(png, info, spec.text, spec.text_count);
  png_write_info(png, info);
  if (spec.depth == 16) png_set_swap(png);  // PNG is big-endian; the rows are in host order
  const std::size_t row_bytes = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.channels) *
                                static_cast<std::size_t>(spec.depth / 8);
  for (int y = 0; y < spec.height; ++y) png_write_row(png, spec.rows + static_cast<std::size_t>(y) * row_bytes);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(file) != 0) {
    std::snprintf(error, 256, "%s", std::strerror(errno));
    return false;
  }
  return true;
}

}  // namespace

std::filesystem::path write_image(const CapturedImage& image, const std::filesystem::path& dir, bool prefer_tiff) {
  const std::filesystem::path path = dir / image_file_name(image, prefer_tiff);
  const std::filesystem::path tmp = temp_path_for(path);
  const int w = image.width, h = image.height;
  int channels = image.channels;
  if (image.plane == "color" && image.bits[3] == 0) channels = 3;  // no alpha plane: RGB file
  OIIO::TypeDesc type = OIIO::TypeDesc::UINT8;
  std::vector<std::uint8_t> bytes;
  std::vector<std::uint16_t> words;
  std::vector<float> floats;
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(channels);
  // Files store rows top first; GL planes bottom first.
  auto src_index = [&](std::size_t x, std::size_t y, int c) {
    const std::size_t row = static_cast<std::size_t>(h - 1) - y;
    return (row * static_cast<std::size_t>(w) + x) * static_cast<std::size_t>(image.channels) + static_cast<std::size_t>(c);
  };
  auto for_each_sample = [&](auto&& f) {
    for (std::size_t y = 0; y < static_cast<std::size_t>(h); ++y)
      for (std::size_t x = 0; x < static_cast<std::size_t>(w); ++x)
        for (int c = 0; c < channels; ++c) f(y, x, c, image.codes[src_index(x, y, c)]);
  };
  const int widest = *std::max_element(image.bits.begin(), image.bits.end());
  const int file_bits = image.plane == "depth" ? 32 : widest > 8 ? 16 : 8;
  if (image.plane == "depth") {
    type = OIIO::TypeDesc::FLOAT;
    floats.resize(count);
    for_each_sample([&](std::size_t y, std::size_t x, int, std::uint32_t k) {
      floats[y * static_cast<std::size_t>(w) + x] = static_cast<float>(fixed_to_float(k, image.bits[0]));
    });
  } else {
    // A code k at n bits becomes round(k·(2^f−1)/(2^n−1)) at the file's f bits: the same
    // fraction, exact when n = f, injective otherwise; its top n bits are k again, which is
    // what sBIT (and a reader's `sample >> (f − n)`) takes (docs/images.md).
    auto to_file = [&](std::uint32_t k, int c) {
      const int n = image.plane == "stencil" ? image.bits[0] : image.bits[c];
      return rescale_code(k, n, file_bits);
    };
    if (file_bits == 8) {
      bytes.resize(count);
      for_each_sample([&](std::size_t y, std::size_t x, int c, std::uint32_t k) {
        bytes[(y * static_cast<std::size_t>(w) + x) * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)] =
            static_cast<std::uint8_t>(image.plane == "stencil" ? std::min<std::uint32_t>(k, 255) : to_file(k, c));
      });
    } else {
      type = OIIO::TypeDesc::UINT16;
      words.resize(count);
      for_each_sample([&](std::size_t y, std::size_t x, int c, std::uint32_t k) {
        words[(y * static_cast<std::size_t>(w) + x) * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)] =
            static_cast<std::uint16_t>(to_file(k, c));
      });
    }
  }
  const std::string note = width_note(image, channels, file_bits);
  std::string widths;
  for (int c = 0; c < (image.plane == "depth" || image.plane == "stencil" ? 1 : channels); ++c)
    widths += fmt::format("{}{}", c ? "," : "", image.bits[static_cast<std::size_t>(c)]);
  if (path.extension() == ".png") {
    PngSpec spec;
    spec.width = w, spec.height = h, spec.channels = channels, spec.depth = file_bits;
    spec.rows = words.empty() ? bytes.data() : reinterpret_cast<const unsigned char*>(words.data());
    if (image.plane != "stencil") {  // stencil values are stored as they are, not scaled
      auto width_of = [&](int c) {
        return static_cast<png_byte>(std::clamp(image.bits[static_cast<std::size_t>(c)], 1, file_bits));
      };
      if (channels <= 2) {
        spec.significant.gray = width_of(0);
        if (channels == 2) spec.significant.alpha = width_of(1);
      } else {
        spec.significant.red = width_of(0), spec.significant.green = width_of(1), spec.significant.blue = width_of(2);
        if (channels == 4) spec.significant.alpha = width_of(3);
      }
    }
    std::string key_bits = "passim:bits", key_note = "Description", key_software = "Software", software = "passim",
                text_note = note;
    png_text text[3] = {};
    text[0].compression = text[1].compression = text[2].compression = PNG_TEXT_COMPRESSION_NONE;
    text[0].key = key_bits.data(), text[0].text = widths.data();
    text[1].key = key_note.data(), text[1].text = text_note.data();
    text[2].key = key_software.data(), text[2].text = software.data();
    spec.text = text, spec.text_count = 3;
    char error[256] = "";
    if (!write_png(tmp.c_str(), spec, error)) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), error));
    }
    commit(tmp, path);
    return path;
  }
  auto out = OIIO::ImageOutput::create(tmp.string());
  if (!out) throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), OIIO::geterror()));
  OIIO::ImageSpec spec(w, h, channels, type);
  if (image.plane == "depth") spec.channelnames = {"Z"};
  spec.attribute("Software", "passim");
  spec.attribute("ImageDescription", note);
  spec.attribute("passim:bits", widths);
  // A TIFF holds the codes at their own width where OpenImageIO writes that width (4, 10, 12,
  // 14 bits: a sample is then the code itself); other widths stay in 8- or 16-bit samples.
  if (image.plane != "depth" && image.plane != "stencil" && widest != file_bits &&
      std::all_of(image.bits.begin(), image.bits.begin() + channels, [&](int b) { return b == widest; }) &&
      (widest == 4 || widest == 10 || widest == 12 || widest == 14))
    spec.attribute("oiio:BitsPerSample", widest);
  // The codes are the framebuffer's, colour not multiplied by alpha: without this OpenImageIO
  // takes RGBA data as premultiplied and divides the colour by alpha when it writes.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open(tmp.string(), spec))
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), out->geterror()));
  const void* data = !floats.empty() ? static_cast<const void*>(floats.data())
                     : !words.empty() ? static_cast<const void*>(words.data())
                                      : static_cast<const void*>(bytes.data());
  const bool ok = out->write_image(type, data);
  const bool closed = out->close();
  if (!ok || !closed) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), out->geterror()));
  }
  commit(tmp, path);
  return path;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = temp_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
    out << text;
    if (!out.flush()) throw std::runtime_error(fmt::format("cannot write {}", path.string()));
  }
  commit(tmp, path);
}

}  // namespace passim
