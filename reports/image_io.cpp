#include "reports/image_io.hpp"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
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
  if (image.plane == "depth") {
    type = OIIO::TypeDesc::FLOAT;
    floats.resize(count);
    for_each_sample([&](std::size_t y, std::size_t x, int, std::uint32_t k) {
      floats[y * static_cast<std::size_t>(w) + x] = static_cast<float>(fixed_to_float(k, image.bits[0]));
    });
  } else {
    const int widest = *std::max_element(image.bits.begin(), image.bits.end());
    const int file_bits = widest > 8 ? 16 : 8;
    // A code k at n bits becomes round(k·(2^f−1)/(2^n−1)) at the file's f bits: the same
    // fraction, exact when n = f, injective otherwise (docs/trace-format.md).
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
  auto out = OIIO::ImageOutput::create(tmp.string());
  if (!out) throw std::runtime_error(fmt::format("cannot write {}: {}", path.string(), OIIO::geterror()));
  OIIO::ImageSpec spec(w, h, channels, type);
  if (image.plane == "depth") spec.channelnames = {"Z"};
  spec.attribute("Software", "passim");
  // The codes are the framebuffer's, colour not multiplied by alpha: without this OpenImageIO
  // takes RGBA data as premultiplied and divides the colour by alpha when it writes a PNG.
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

void write_rgb8(const std::filesystem::path& file, int width, int height, const std::vector<std::uint8_t>& top_first) {
  CapturedImage img;
  img.name = file.stem().string();
  img.plane = "rgb";
  img.width = width;
  img.height = height;
  img.channels = 3;
  img.bits = {8, 8, 8, 0};
  img.codes.resize(top_first.size());
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y)  // CapturedImage rows are bottom first
    std::copy_n(top_first.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row), row,
                img.codes.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(height - 1 - y) * row));
  write_image(img, file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path());
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
