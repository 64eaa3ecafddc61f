// Image files hold the framebuffer's codes exactly (docs/trace-format.md "Image files").
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>
#include <png.h>

#include <cstdio>

#include <filesystem>

#include "reports/image_io.hpp"
#include "trace_io/trace.hpp"

namespace passim {
namespace {

// Reads a file's samples as stored, colour not multiplied by alpha.
std::vector<std::uint16_t> read_raw(const std::filesystem::path& file, OIIO::TypeDesc type) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(file.string(), &config);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  const OIIO::ImageSpec& s = in->spec();
  std::vector<std::uint16_t> v(static_cast<std::size_t>(s.width * s.height * s.nchannels));
  if (type == OIIO::TypeDesc::UINT8) {
    std::vector<std::uint8_t> b(v.size());
    in->read_image(0, 0, 0, s.nchannels, type, b.data());
    std::copy(b.begin(), b.end(), v.begin());
  } else {
    in->read_image(0, 0, 0, s.nchannels, type, v.data());
  }
  return v;
}

// An RGBA colour with a small alpha must come back unchanged: OpenImageIO would otherwise
// treat it as premultiplied and store 200/64*255 (saturated) instead of 200.
TEST(ImageFiles, RgbaPngKeepsColourWhereAlphaIsSmall) {
  const auto dir = std::filesystem::temp_directory_path() / "passim-image-io-test";
  std::filesystem::create_directories(dir);
  for (int bits : {8, 12}) {
    CapturedImage img;
    img.name = "rgba" + std::to_string(bits);
    img.plane = "color";
    img.width = 2;
    img.height = 1;
    img.channels = 4;
    img.bits = {bits, bits, bits, bits};
    const std::uint32_t max = (1u << bits) - 1;
    // Pixel 0: colour 200/255 of full scale, alpha 64/255; pixel 1: alpha 0.
    const std::uint32_t c = bits == 8 ? 200 : 3212, a = bits == 8 ? 64 : 1028;
    img.codes = {c, c / 2, 7, a, max, 1, 0, 0};
    const auto file = write_image(img, dir);
    const auto raw = read_raw(file, bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16);
    ASSERT_EQ(raw.size(), 8u);
    // 8 bits: stored as is; 12 bits: k * 65535 / 4095 = k * 16.0037 rounded (by hand below).
    const std::vector<std::uint16_t> want =
        bits == 8 ? std::vector<std::uint16_t>{200, 100, 7, 64, 255, 1, 0, 0}
                  : std::vector<std::uint16_t>{51404, 25702, 112, 16452, 65535, 16, 0, 0};
    EXPECT_EQ(raw, want) << bits << " bits";
  }
}

// A PNG's significant bits (sBIT) and samples, read with libpng as any PNG reader would.
struct PngRead {
  png_color_8 sbit{};
  bool has_sbit = false;
  int depth = 0, channels = 0;
  std::vector<std::uint32_t> samples;
};
PngRead read_png(const std::filesystem::path& file) {
  PngRead r;
  FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) return r;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    return r;
  }
  png_init_io(png, f);
  png_read_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_color_8p sbit = nullptr;
  if (png_get_sBIT(png, info, &sbit)) r.sbit = *sbit, r.has_sbit = true;
  r.depth = png_get_bit_depth(png, info);
  r.channels = png_get_channels(png, info);
  const png_bytepp rows = png_get_rows(png, info);
  const std::size_t per_row = png_get_image_width(png, info) * static_cast<std::size_t>(r.channels);
  for (png_uint_32 y = 0; y < png_get_image_height(png, info); ++y)
    for (std::size_t k = 0; k < per_row; ++k)
      r.samples.push_back(r.depth == 16 ? (static_cast<std::uint32_t>(rows[y][2 * k]) << 8) | rows[y][2 * k + 1]
                                        : rows[y][k]);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  return r;
}

// The true width survives in the file (docs/images.md): the sBIT chunk names it, and the top
// `bits` bits of each sample are the code (a code k at n bits is stored as round(k·(2^f − 1) /
// (2^n − 1)) = k·2^(f−n) + a remainder below 2^(f−n), derived in docs/images.md).
TEST(ImageFiles, PngKeepsTheTrueWidthInSbit) {
  const auto dir = std::filesystem::temp_directory_path() / "passim-image-io-sbit";
  std::filesystem::create_directories(dir);
  for (int bits : {1, 4, 6, 9, 12, 15}) {
    CapturedImage img;
    img.name = "grey" + std::to_string(bits);
    img.plane = "alpha";
    img.width = 4;
    img.height = 1;
    img.channels = 1;
    img.bits = {bits, 0, 0, 0};
    const std::uint32_t max = (1u << bits) - 1;
    img.codes = {0, 1, max / 2, max};
    const PngRead r = read_png(write_image(img, dir));
    ASSERT_TRUE(r.has_sbit) << bits;
    EXPECT_EQ(r.sbit.gray, bits);
    const int file_bits = bits > 8 ? 16 : 8;
    EXPECT_EQ(r.depth, file_bits);
    ASSERT_EQ(r.samples.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(r.samples[k] >> (file_bits - bits), img.codes[k]) << bits;
  }
  // RGB at 10 bits: one width per channel.
  CapturedImage rgb;
  rgb.name = "rgb10";
  rgb.plane = "rgb";
  rgb.width = 1;
  rgb.height = 1;
  rgb.channels = 3;
  rgb.bits = {10, 10, 10, 0};
  rgb.codes = {1023, 512, 3};
  const PngRead r = read_png(write_image(rgb, dir));
  EXPECT_EQ(r.sbit.red, 10);
  EXPECT_EQ(r.sbit.green, 10);
  EXPECT_EQ(r.sbit.blue, 10);
  EXPECT_EQ(r.samples, (std::vector<std::uint32_t>{65535, 32800, 192}));  // round(k·65535/1023) by hand
}

}  // namespace
}  // namespace passim
