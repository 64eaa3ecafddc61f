// Image files hold the framebuffer's codes exactly (docs/trace-format.md "Image files").
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

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

}  // namespace
}  // namespace passim
