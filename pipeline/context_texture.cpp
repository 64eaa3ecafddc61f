// Context: texture objects (§3.8.12), images and their copies (§3.8.1-3.8.3) and texture
// parameters (§3.8.4).
#include <algorithm>
#include <limits>
#include <cmath>
#include <fmt/format.h>

#include "client/glu_mipmaps.hpp"
#include "client/pixel_pack.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/kernel_paths.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

// ---------------------------------------------------------------- texture objects (§3.8.12)

TextureObject* Context::texture_for(GLenum target) {
  if (target == GL_TEXTURE_1D)
    return textures_.bound_1d ? &textures_.objects[textures_.bound_1d] : &textures_.default_1d;
  if (target == GL_TEXTURE_2D)
    return textures_.bound_2d ? &textures_.objects[textures_.bound_2d] : &textures_.default_2d;
  return nullptr;
}

const TextureObject* Context::bound_texture(GLenum target) const {
  return const_cast<Context*>(this)->texture_for(target);
}

void Context::glGenTextures(GLsizei n, GLuint* textures) {
  PASSIM_ENTRY(n, textures)
  if (n < 0) return set_error(GL_INVALID_VALUE);
  GLuint next = 1;
  for (GLsizei k = 0; k < n; ++k) {
    while (textures_.reserved.count(next) || textures_.objects.count(next)) ++next;
    textures_.reserved[next] = true;
    textures[k] = next;
  }
}

void Context::glDeleteTextures(GLsizei n, const GLuint* textures) {
  PASSIM_ENTRY(n, textures)
  if (n < 0) return set_error(GL_INVALID_VALUE);
  for (GLsizei k = 0; k < n; ++k) {
    const GLuint name = textures[k];
    if (name == 0) continue;
    // §3.8.12: a deleted bound texture reverts the binding to 0.
    if (textures_.bound_1d == name) textures_.bound_1d = 0;
    if (textures_.bound_2d == name) textures_.bound_2d = 0;
    if (auto it = textures_.objects.find(name); it != textures_.objects.end())
      for (const TextureLevel& l : it->second.levels) memory_.release(l.bytes());
    textures_.objects.erase(name);
    textures_.reserved.erase(name);
  }
}

void Context::glBindTexture(GLenum target, GLuint texture) {
  PASSIM_ENTRY(target, texture)
  if (target != GL_TEXTURE_1D && target != GL_TEXTURE_2D) return set_error(GL_INVALID_ENUM);
  if (texture != 0) {
    auto it = textures_.objects.find(texture);
    if (it != textures_.objects.end() && it->second.target != target) return set_error(GL_INVALID_OPERATION);
    if (it == textures_.objects.end()) textures_.objects[texture].target = target;
  }
  (target == GL_TEXTURE_1D ? textures_.bound_1d : textures_.bound_2d) = texture;
}

GLboolean Context::glIsTexture(GLuint texture) {
  PASSIM_ENTRY_RET(GL_FALSE, texture)
  return texture != 0 && textures_.objects.count(texture) ? GL_TRUE : GL_FALSE;
}
// ---------------------------------------------------------------- images (§3.8.1-3.8.3)

namespace {

bool is_power_of_two(int v) { return v > 0 && (v & (v - 1)) == 0; }

bool is_texture_format(GLenum format) { return is_color_pixel_format(format) || format == GL_DEPTH_COMPONENT; }

int log2_floor(int v) {
  int l = 0;
  while (v > 1) {
    v >>= 1;
    ++l;
  }
  return l;
}

// Table 3.15: the codes kept for a base format, from a clamped RGBA group.
void texel_codes(const InternalFormat& f, const Rgba& c, std::uint32_t* out) {
  auto q = [](double v, int bits) { return float_to_fixed(v, bits); };  // clamps to [0, 1], rounds (§3.8.1)
  out[0] = out[1] = out[2] = out[3] = 0;
  switch (f.base) {
    case GL_ALPHA: out[3] = q(c[3], f.alpha); break;
    case GL_LUMINANCE: out[0] = q(c[0], f.luminance); break;
    case GL_LUMINANCE_ALPHA: out[0] = q(c[0], f.luminance); out[3] = q(c[3], f.alpha); break;
    case GL_INTENSITY: out[0] = q(c[0], f.intensity); break;
    case GL_RGB: out[0] = q(c[0], f.red); out[1] = q(c[1], f.green); out[2] = q(c[2], f.blue); break;
    default:
      out[0] = q(c[0], f.red);
      out[1] = q(c[1], f.green);
      out[2] = q(c[2], f.blue);
      out[3] = q(c[3], f.alpha);
      break;
  }
}

int texel_bits(const InternalFormat& f) {
  return f.red + f.green + f.blue + f.alpha + f.luminance + f.intensity + f.depth;
}

}  // namespace

namespace {
// Rows [y0, y0 + height) of `level` from x0 on, from width × height values (colour or depth).
// The caller has marked the level's texels changed, and counts the bits written.
void write_texels(TextureLevel& level, int x0, int y0, int width, int height, const Rgba* rgba, const double* depth) {
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::size_t src = static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
      std::uint32_t codes[4] = {0, 0, 0, 0};
      if (depth) codes[0] = float_to_fixed(depth[src], level.format.depth);
      else texel_codes(level.format, rgba[src], codes);
      level.set_texel(static_cast<std::size_t>(y0 + y) * static_cast<std::size_t>(level.width) + static_cast<std::size_t>(x0 + x),
                      codes);
    }
}
}  // namespace

void Context::store_texels(TextureLevel& level, int x0, int y0, int width, int height, const std::vector<Rgba>& rgba,
                           const std::vector<double>* depth) {
  level.texels_changed();
  const auto rows = [&](int first, int end) {
    const std::size_t skip = static_cast<std::size_t>(first) * static_cast<std::size_t>(width);
    write_texels(level, x0, y0 + first, width, end - first, depth ? nullptr : rgba.data() + skip,
                 depth ? depth->data() + skip : nullptr);
  };
  const RowSplitter* split = rows_on_lanes();
  split ? (*split)(height, rows) : rows(0, height);
  counters().texture_bits_written += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) *
                                     static_cast<std::uint64_t>(texel_bits(level.format));
}

void Context::copy_color_texels(int dims, int x, int y, int width, int height, TextureLevel& level, int x0, int y0,
                                int store_width, int store_height) {
  constexpr int kBandRows = 16;
  const std::uint64_t n = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  const SourceCodes source = read_framebuffer_codes(x, y, width, height, nullptr);  // nothing draws meanwhile
  const std::vector<Rgba> table_reals = transfer_table(source, dims, n);
  if (table_reals.empty() && (!scratch_->lanes || active_convolution(transfer_, dims) || transfer_.histogram.enabled ||
                              transfer_.minmax.enabled || height <= kBandRows)) {
    std::vector<Rgba> rgba;
    std::vector<double> unused;
    read_for_texture(false, dims, x, y, width, height, rgba, unused);
    if (!rgba.empty()) store_texels(level, x0, y0, store_width, store_height, rgba, nullptr);
    return;
  }
  // Every step is per pixel (read_for_texture's counting, then the transfer's and the
  // stores').
  Counters& c = counters();
  const FramebufferConfig& f = fb_.config;
  c.pixels_read += n;
  c.color_bits_read += n * static_cast<std::uint64_t>(f.color_bits[0] + f.color_bits[1] + f.color_bits[2] + f.color_bits[3]);
  level.texels_changed();
  if (!table_reals.empty()) {
    // Per component: each code's texel codes found once (write_texels's conversion of its
    // transferred reals), then looked up per texel, by ranges of rows on the lanes. A stored
    // component is one of the source's own (Table 3.15: L and I from R), so output component
    // k is a function of source component k alone; unstored components are 0 in every entry.
    // (A colour level's codes are at most 16 bits wide: TextureLevel::texels holds them.)
    std::vector<std::uint16_t> table(4 * table_reals.size());
    for (std::size_t i = 0; i < table_reals.size(); ++i) {
      std::uint32_t codes[4];
      texel_codes(level.format, table_reals[i], codes);
      std::copy_n(codes, 4, &table[4 * i]);
    }
    count_transfer(transfer_, transform_.color.back(), n, n, c);
    const std::size_t level_width = static_cast<std::size_t>(level.width);
    const auto rows = [&](int first, int end) {
      std::uint16_t* out =
          &level.texels[4 * (static_cast<std::size_t>(y0 + first) * level_width + static_cast<std::size_t>(x0))];
      source.through_table(first, end - first, table.data(), out, 4 * level_width);
    };
    const RowSplitter* split = rows_on_lanes();
    split ? (*split)(height, rows) : rows(0, height);
  } else {
    // Each lane converts, transfers and stores whole bands of rows (the transfer's counters
    // per lane: sums).
    transfer_bands_on_lanes(source, width, height, dims, kBandRows, nullptr,
                            [&](LaneStages&, const Rgba* band, int first_row, int rows) {
                              write_texels(level, x0, y0 + first_row, width, rows, band, nullptr);
                            });
  }
  c.texture_bits_written += n * static_cast<std::uint64_t>(texel_bits(level.format));
}

void Context::tex_image(GLenum target, int dims, GLint level, GLint internalformat, GLsizei width, GLsizei height,
                        GLint border, GLenum format, GLenum type, const void* pixels, bool overwritten) {
  const GLenum want = dims == 1 ? GL_TEXTURE_1D : GL_TEXTURE_2D;
  if (target != want) return set_error(GL_INVALID_ENUM);
  const int max = profile_.limits.max_texture_size;
  if (level < 0 || level > log2_floor(max)) return set_error(GL_INVALID_VALUE);
  const auto fmt_info = internal_format(internalformat);
  if (!fmt_info) return set_error(GL_INVALID_VALUE);
  if (border != 0 && border != 1) return set_error(GL_INVALID_VALUE);
  // The size checks use the size after a REDUCE convolution (§3.8.1), even without data.
  const int source_width = width, source_height = dims == 2 ? height : 1;
  if (format != GL_DEPTH_COMPONENT) reduced_size(dims, width, height);
  const int w = width - 2 * border, h = dims == 2 ? height - 2 * border : 1;
  if (width < 0 || height < 0 || !is_power_of_two(w) || !is_power_of_two(h) || w > max || h > max)
    return set_error(GL_INVALID_VALUE);
  if (!is_texture_format(format)) return set_error(GL_INVALID_ENUM);
  if (!is_pixel_type(type)) return set_error(GL_INVALID_ENUM);
  if (static_cast<std::int64_t>(width) * (dims == 2 ? height : 1) > profile_.limits.max_texture_texels)
    return set_error(GL_OUT_OF_MEMORY);
  if ((format == GL_DEPTH_COMPONENT) != (fmt_info->base == GL_DEPTH_COMPONENT)) return set_error(GL_INVALID_OPERATION);
  // Without a convolution, histogram or minmax (which see the whole image at once), the image
  // goes through the pixel path in bands of rows: the scratch reals are a band's, so a 4096²
  // RGBA8 level loads with 4 MiB of scratch rather than 512 MiB. Every step is per pixel and
  // counts per pixel: the bands give the same texels and counters.
  constexpr int kBandRows = 32;
  const bool banded = format != GL_DEPTH_COMPONENT && !active_convolution(transfer_, dims) &&
                      !transfer_.histogram.enabled && !transfer_.minmax.enabled &&
                      pixel_store_.unpack.skip_rows <= std::numeric_limits<int>::max() - source_height;
  if (pixels && !rectangle_fits_in_memory(source_width, banded ? std::min(kBandRows, source_height) : source_height))
    return;
  TextureObject& tex = *texture_for(target);
  // §2.5: the level is charged to the budget (the level it replaces released): OUT_OF_MEMORY
  // when it does not fit, and the old level stays.
  const std::uint64_t old_bytes = static_cast<std::size_t>(level) < tex.levels.size()
                                      ? tex.levels[static_cast<std::size_t>(level)].bytes()
                                      : 0;
  const std::uint64_t new_bytes = TextureLevel::bytes_for(width, dims == 2 ? height : 1);
  if (new_bytes > old_bytes && !memory_.try_charge(new_bytes - old_bytes)) return set_error(GL_OUT_OF_MEMORY);
  if (new_bytes < old_bytes) memory_.release(old_bytes - new_bytes);
  tex.target = target;
  if (tex.levels.size() <= static_cast<std::size_t>(level)) tex.levels.resize(static_cast<std::size_t>(level) + 1);
  TextureLevel& l = tex.levels[static_cast<std::size_t>(level)];
  l.width = width;
  l.height = dims == 2 ? height : 1;
  l.border = border;
  l.format = *fmt_info;
  const std::size_t values = 4 * static_cast<std::size_t>(l.width) * static_cast<std::size_t>(l.height);
  if (overwritten) l.texels.resize(values);
  else l.texels.assign(values, 0);
  l.texels_changed();
  if (!pixels) return;  // §3.8.1: a NULL image defines the level with unspecified contents (zeros here)
  std::vector<Rgba> rgba;
  std::vector<double> depth;
  // §3.8.1: the DrawPixels path (unpack, pixel transfer) up to the final conversion.
  if (banded) {
    for (int first = 0; first < source_height; first += kBandRows) {
      const int rows = std::min(kBandRows, source_height - first);
      PixelStore band = pixel_store_.unpack;
      band.skip_rows += first;  // §3.6.4: the band's first row, as the image's row `first`
      unpack_rgba(pixels, source_width, rows, format, type, band, rgba);
      int tw = source_width, th = rows;
      transfer_rgba(rgba, tw, th, transfer_, transform_.color.back(), counters(), dims);  // no sink: true
      store_texels(l, 0, first, l.width, rows, rgba, nullptr);
    }
    return;
  }
  if (format == GL_DEPTH_COMPONENT) {
    unpack_depth(pixels, l.width, l.height, type, pixel_store_.unpack, depth);
    transfer_depth(depth, transfer_);
  } else {
    unpack_rgba(pixels, source_width, source_height, format, type, pixel_store_.unpack, rgba);
    int tw = source_width, th = source_height;
    // A sink consumes the pixels: the texels are not changed (the level is still defined).
    if (!transfer_rgba(rgba, tw, th, transfer_, transform_.color.back(), counters(), dims)) return;
  }
  store_texels(l, 0, 0, l.width, l.height, rgba, format == GL_DEPTH_COMPONENT ? &depth : nullptr);
}

void Context::glTexImage1D(GLenum target, GLint level, GLint internalformat, GLsizei width, GLint border, GLenum format,
                           GLenum type, const void* pixels) {
  PASSIM_ENTRY(target, level, internalformat, width, border, format, type,
               pixels)
  tex_image(target, 1, level, internalformat, width, 1, border, format, type, pixels);
}

void Context::glTexImage2D(GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height,
                           GLint border, GLenum format, GLenum type, const void* pixels) {
  PASSIM_ENTRY(target, level, internalformat, width, height, border, format, type,
               pixels)
  tex_image(target, 2, level, internalformat, width, height, border, format, type, pixels);
}

GLint Context::gluBuild1DMipmaps(GLenum target, GLint internalformat, GLsizei width, GLenum format, GLenum type,
                                 const void* data) {
  PASSIM_ENTRY_RET(0, target, internalformat, width, format, type, data)
  return build_mipmaps(target, 1, internalformat, width, 1, format, type, data);
}

GLint Context::gluBuild2DMipmaps(GLenum target, GLint internalformat, GLsizei width, GLsizei height, GLenum format,
                                 GLenum type, const void* data) {
  PASSIM_ENTRY_RET(0, target, internalformat, width, height, format, type, data)
  return build_mipmaps(target, 2, internalformat, width, height, format, type, data);
}

GLint Context::build_mipmaps(GLenum target, int dims, GLint internalformat, int width, int height, GLenum format,
                             GLenum type, const void* data) {
  constexpr GLint kGluInvalidEnum = 100900, kGluInvalidValue = 100901;  // GLU 1.3, glu.h
  const char* name = dims == 1 ? "gluBuild1DMipmaps" : "gluBuild2DMipmaps";
  if (width < 1 || height < 1) return kGluInvalidValue;
  if (target != (dims == 1 ? GL_TEXTURE_1D : GL_TEXTURE_2D)) return kGluInvalidEnum;
  if (!(is_color_pixel_format(format) || format == GL_DEPTH_COMPONENT) || !is_pixel_type(type)) {
    warn_once(fmt::format("{}: format {} with type {} is not modelled (GLU_INVALID_ENUM returned)", name,
                          enum_name(format), enum_name(type)));
    return kGluInvalidEnum;
  }
  if (!is_power_of_two(width) || !is_power_of_two(height)) {
    warn_once(fmt::format("{}: a {}x{} image would first be scaled by gluScaleImage, which is not modelled "
                          "(GLU_INVALID_VALUE returned, no level specified)", name, width, height));
    return kGluInvalidValue;
  }
  if (!data) {
    warn_once(fmt::format("{} without data: GLU_INVALID_VALUE returned", name));
    return kGluInvalidValue;
  }
  const int n = format_components(format);
  std::vector<double> image;
  unpack_elements(data, width, height, format, type, pixel_store_.unpack, image);
  // GLU's closest fit: an image larger than MAX_TEXTURE_SIZE loses its top levels.
  const int max = profile_.limits.max_texture_size;
  int w = width, h = height;
  auto halve = [&] {
    image = glu_halve_image(image, w, h, n, type);
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
  };
  while (w > max || h > max) halve();
  // Its own images are tightly packed; the application's unpack modes are restored after.
  const PixelStore application = pixel_store_.unpack;
  pixel_store_.unpack = PixelStore{};
  pixel_store_.unpack.alignment = 1;
  for (int level = 0;; ++level) {
    const std::vector<std::byte> bytes = pack_elements(image, type);
    tex_image(target, dims, level, internalformat, w, h, 0, format, type, bytes.data());
    if (w == 1 && h == 1) break;
    halve();
  }
  pixel_store_.unpack = application;
  return 0;
}

void Context::reduced_size(int dims, int& width, int& height) const {
  const ConvolutionFilter* f = active_convolution(transfer_, dims);
  if (!f || f->border_mode != GL_REDUCE) return;
  width = width - f->width + 1;
  if (dims == 2) height = height - f->height + 1;
}

TextureLevel* Context::sub_image_level(GLenum target, int dims, GLint level, GLint xoffset, GLint yoffset,
                                       GLsizei width, GLsizei height) {
  // §3.8.2: the level must exist and the rectangle lie inside it (borders included). The
  // target is the callers' first check (tex_sub_image, copy_tex_sub_image).
  TextureObject& tex = *texture_for(target);
  if (level < 0 || static_cast<std::size_t>(level) >= tex.levels.size() || !tex.levels[level].defined()) {
    set_error(level < 0 ? GL_INVALID_VALUE : GL_INVALID_OPERATION);
    return nullptr;
  }
  TextureLevel& l = tex.levels[static_cast<std::size_t>(level)];
  const int b = l.border;
  if (width < 0 || height < 0 || xoffset < -b || xoffset + width > l.width - b ||
      (dims == 2 && (yoffset < -b || yoffset + height > l.height - b))) {
    set_error(GL_INVALID_VALUE);
    return nullptr;
  }
  return &l;
}

void Context::read_for_texture(bool depth, int dims, int x, int y, int width, int height, std::vector<Rgba>& rgba,
                               std::vector<double>& values) {
  Counters& c = counters();
  const std::uint64_t n = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  const FramebufferConfig& f = fb_.config;
  c.pixels_read += n;
  // §3.8.2: texture copies read like CopyPixels, through the pixel-transfer operations.
  if (depth) {
    read_framebuffer_depth(x, y, width, height, values);
    c.depth_bits_read += n * static_cast<std::uint64_t>(f.depth_bits);
    transfer_depth(values, transfer_);
  } else {
    const RowSplitter* split = rows_on_lanes();
    read_framebuffer_rgba(x, y, width, height, rgba, split);
    c.color_bits_read +=
        n * static_cast<std::uint64_t>(f.color_bits[0] + f.color_bits[1] + f.color_bits[2] + f.color_bits[3]);
    int w = width, h = height;
    if (!transfer_rgba(rgba, w, h, transfer_, transform_.color.back(), c, dims, nullptr, split)) rgba.clear();
  }
}

void Context::tex_sub_image(GLenum target, int dims, GLint level, GLint xoffset, GLint yoffset, GLsizei width,
                            GLsizei height, GLenum format, GLenum type, const void* pixels) {
  if (target != (dims == 1 ? GL_TEXTURE_1D : GL_TEXTURE_2D)) return set_error(GL_INVALID_ENUM);
  if (!is_texture_format(format) || !is_pixel_type(type)) return set_error(GL_INVALID_ENUM);
  const int source_width = width, source_height = height;
  if (format != GL_DEPTH_COMPONENT) reduced_size(dims, width, height);
  TextureLevel* level_ptr = sub_image_level(target, dims, level, xoffset, yoffset, width, height);
  if (!level_ptr) return;
  TextureLevel& l = *level_ptr;
  const int b = l.border;
  if ((format == GL_DEPTH_COMPONENT) != (l.format.base == GL_DEPTH_COMPONENT)) return set_error(GL_INVALID_OPERATION);
  if (width == 0 || height == 0 || !pixels) return;
  if (!rectangle_fits_in_memory(source_width, source_height)) return;
  std::vector<Rgba> rgba;
  std::vector<double> depth;
  if (format == GL_DEPTH_COMPONENT) {
    unpack_depth(pixels, width, height, type, pixel_store_.unpack, depth);
    transfer_depth(depth, transfer_);
  } else {
    unpack_rgba(pixels, source_width, source_height, format, type, pixel_store_.unpack, rgba);
    int tw = source_width, th = source_height;
    if (!transfer_rgba(rgba, tw, th, transfer_, transform_.color.back(), counters(), dims)) return;
  }
  store_texels(l, xoffset + b, dims == 2 ? yoffset + b : 0, width, height, rgba,
               format == GL_DEPTH_COMPONENT ? &depth : nullptr);
}

void Context::glTexSubImage1D(GLenum target, GLint level, GLint xoffset, GLsizei width, GLenum format, GLenum type,
                              const void* pixels) {
  PASSIM_ENTRY(target, level, xoffset, width, format, type,
               pixels)
  tex_sub_image(target, 1, level, xoffset, 0, width, 1, format, type, pixels);
}

void Context::glTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei width, GLsizei height,
                              GLenum format, GLenum type, const void* pixels) {
  PASSIM_ENTRY(target, level, xoffset, yoffset, width, height, format, type,
               pixels)
  tex_sub_image(target, 2, level, xoffset, yoffset, width, height, format, type, pixels);
}

Context::SourceCodes Context::read_framebuffer_codes(int x, int y, int width, int height,
                                                     std::vector<std::uint16_t>* copy) const {
  SourceCodes src;
  src.width = width;
  src.height = height;
  const auto& bits = fb_.config.color_bits;
  for (int k = 0; k < 4; ++k) {
    src.values[k] = bits[k] ? code_values(bits[k]) : nullptr;
    src.bits[k] = bits[k];
  }
  auto inside = [](int origin, int size, int limit, int& lo, int& hi) {
    const auto first = std::clamp<std::int64_t>(-std::int64_t{origin}, 0, size);
    lo = static_cast<int>(first);
    hi = static_cast<int>(std::clamp<std::int64_t>(std::int64_t{limit} - origin, first, size));
  };
  inside(x, width, fb_.width(), src.i_lo, src.i_hi);
  inside(y, height, fb_.height(), src.j_lo, src.j_hi);
  const std::size_t row = 4 * static_cast<std::size_t>(src.i_hi - src.i_lo);
  if (row == 0 || src.j_hi <= src.j_lo) return src;
  const ColorPlane* plane = color_buffer(pixel_.read_buffer);
  const std::uint16_t* origin = &plane->rgba[4 * fb_.pixel_index(x + src.i_lo, y + src.j_lo)];
  const std::size_t plane_stride = 4 * static_cast<std::size_t>(fb_.width());
  if (!copy) {
    src.first = origin;
    src.stride = plane_stride;
    return src;
  }
  copy->resize(row * static_cast<std::size_t>(src.j_hi - src.j_lo));
  for (int j = 0; j < src.j_hi - src.j_lo; ++j)
    std::copy_n(origin + plane_stride * static_cast<std::size_t>(j), row,
                copy->begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(j)));
  src.first = copy->data();
  src.stride = row;
  return src;
}

std::size_t Context::SourceCodes::table_entries() const {
  return (std::size_t{1} << std::max({bits[0], bits[1], bits[2], bits[3]})) + 1;
}

std::vector<Rgba> Context::SourceCodes::table_reals() const {
  const std::size_t inside = table_entries() - 1;
  std::vector<Rgba> reals(inside + 1, Rgba{0, 0, 0, 0});  // the last: outside the window
  for (std::size_t i = 0; i < inside; ++i)
    for (std::size_t k = 0; k < 4; ++k)
      reals[i][k] = values[k] ? values[k][std::min(i, (std::size_t{1} << bits[k]) - 1)] : 1.0;
  return reals;
}

template <class Code>
void Context::SourceCodes::through_table(int first_row, int rows, const Code* table, Code* out,
                                         std::size_t out_stride) const {
  const Code* outside = table + 4 * (table_entries() - 1);
  const auto put_outside = [&](Code* o, int from, int to) {
    for (int i = from; i < to; ++i) std::copy_n(outside, 4, o + 4 * i);
  };
  for (int j = first_row; j < first_row + rows; ++j) {
    Code* o = out + static_cast<std::size_t>(j - first_row) * out_stride;
    if (j < j_lo || j >= j_hi || i_lo >= i_hi) {
      put_outside(o, 0, width);
      continue;
    }
    put_outside(o, 0, i_lo);
    put_outside(o, i_hi, width);
    const std::uint16_t* c = first + stride * static_cast<std::size_t>(j - j_lo);
    for (int i = i_lo; i < i_hi; ++i, c += 4)
      for (std::size_t k = 0; k < 4; ++k) o[4 * i + k] = table[4 * std::size_t{c[k]} + k];
  }
}
template void Context::SourceCodes::through_table(int, int, const std::uint16_t*, std::uint16_t*, std::size_t) const;

std::vector<Rgba> Context::transfer_table(const SourceCodes& source, int dims, std::uint64_t pixels) {
  const Mat4& matrix = transform_.color.back();
  // A fast path (the reference transfers every pixel).
  if (!use_specialised() || !transfer_per_component(transfer_, matrix, dims) || source.table_entries() > pixels)
    return {};
  std::vector<Rgba> reals = source.table_reals();
  transfer_per_pixel_steps(transfer_, matrix, reals.data(), reals.size());
  return reals;
}

void Context::SourceCodes::to_reals(int first_row, int rows, Rgba* out) const {
  const std::size_t w = static_cast<std::size_t>(width);
  for (int j = first_row; j < first_row + rows; ++j) {
    Rgba* o = out + static_cast<std::size_t>(j - first_row) * w;
    if (j < j_lo || j >= j_hi || i_lo >= i_hi) {
      std::fill(o, o + w, Rgba{0, 0, 0, 0});
      continue;
    }
    std::fill(o, o + i_lo, Rgba{0, 0, 0, 0});
    std::fill(o + i_hi, o + w, Rgba{0, 0, 0, 0});
    const std::uint16_t* c = first + stride * static_cast<std::size_t>(j - j_lo);
    for (int i = i_lo; i < i_hi; ++i, c += 4)
      for (int k = 0; k < 4; ++k) o[i][static_cast<std::size_t>(k)] = values[k] ? values[k][c[k]] : 1.0;
  }
}

void Context::read_framebuffer_rgba(int x, int y, int width, int height, std::vector<Rgba>& out,
                                    const RowSplitter* split) const {
  // Read in place: nothing draws between the reading and the conversion.
  const SourceCodes src = read_framebuffer_codes(x, y, width, height, nullptr);
  out.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  const auto convert = [&](int first, int end) {
    src.to_reals(first, end - first, out.data() + static_cast<std::size_t>(first) * static_cast<std::size_t>(width));
  };
  split ? (*split)(height, convert) : convert(0, height);
}

void Context::read_framebuffer_depth(int x, int y, int width, int height, std::vector<double>& out) const {
  out.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const int px = x + i, py = y + j;
      if (px < 0 || py < 0 || px >= fb_.width() || py >= fb_.height()) continue;
      out[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)] =
          fixed_to_float(fb_.depth[fb_.pixel_index(px, py)], fb_.config.depth_bits);
    }
}

void Context::copy_tex_image(GLenum target, int dims, GLint level, GLenum internalformat, GLint x, GLint y,
                             GLsizei width, GLsizei height, GLint border) {
  const auto f = internal_format(static_cast<GLint>(internalformat));
  // §3.8.2: internalformat 1-4 are not accepted by CopyTexImage.
  if (f && internalformat >= 1 && internalformat <= 4) return set_error(GL_INVALID_VALUE);
  if (f && f->base == GL_DEPTH_COMPONENT && fb_.config.depth_bits == 0) return set_error(GL_INVALID_OPERATION);
  const std::size_t errors = error_log_.size();
  // A colour copy stores every texel unless a histogram or minmax sink consumes the pixels
  // or a convolution changes the size (then the level starts from zeros).
  const bool overwritten = !(f && f->base == GL_DEPTH_COMPONENT) && !active_convolution(transfer_, dims) &&
                           !transfer_.histogram.enabled && !transfer_.minmax.enabled;
  tex_image(target, dims, level, static_cast<GLint>(internalformat), width, height, border,
            f && f->base == GL_DEPTH_COMPONENT ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, nullptr, overwritten);
  if (error_log_.size() != errors) return;
  // After tex_image's size checks (§3.8.2: a width past the limits is INVALID_VALUE, not a
  // rectangle too large to read); past the budget, §2.5 leaves the level undefined.
  TextureLevel& l = texture_for(target)->levels[static_cast<std::size_t>(level)];
  if (!rectangle_fits_in_memory(width, dims == 2 ? height : 1)) {
    // The level was defined to be overwritten, its codes unset: zeros, so that every code
    // stays below its width (the decoding tables are indexed by them).
    std::fill(l.texels.begin(), l.texels.end(), std::uint16_t{0});
    return;
  }
  // The source rectangle is read whole; a REDUCE convolution brings it to the level's size.
  if (l.format.base != GL_DEPTH_COMPONENT)
    return copy_color_texels(dims, x, y, width, dims == 2 ? height : 1, l, 0, 0, l.width, l.height);
  std::vector<Rgba> unused;
  std::vector<double> depth;
  read_for_texture(true, dims, x, y, width, dims == 2 ? height : 1, unused, depth);
  store_texels(l, 0, 0, l.width, l.height, unused, &depth);
}

void Context::glCopyTexImage1D(GLenum target, GLint level, GLenum internalformat, GLint x, GLint y, GLsizei width,
                               GLint border) {
  PASSIM_ENTRY(target, level, internalformat, x, y, width, border)
  copy_tex_image(target, 1, level, internalformat, x, y, width, 1, border);
}

void Context::glCopyTexImage2D(GLenum target, GLint level, GLenum internalformat, GLint x, GLint y, GLsizei width,
                               GLsizei height, GLint border) {
  PASSIM_ENTRY(target, level, internalformat, x, y, width, height, border)
  copy_tex_image(target, 2, level, internalformat, x, y, width, height, border);
}

void Context::copy_tex_sub_image(GLenum target, int dims, GLint level, GLint xoffset, GLint yoffset, GLint x, GLint y,
                                 GLsizei width, GLsizei height) {
  if (target != (dims == 1 ? GL_TEXTURE_1D : GL_TEXTURE_2D)) return set_error(GL_INVALID_ENUM);
  const TextureObject& tex_probe = *texture_for(target);
  const bool probe_depth = level >= 0 && static_cast<std::size_t>(level) < tex_probe.levels.size() &&
                           tex_probe.levels[static_cast<std::size_t>(level)].format.base == GL_DEPTH_COMPONENT;
  const int source_width = width, source_height = height;
  if (!probe_depth) reduced_size(dims, width, height);
  TextureLevel* level_ptr = sub_image_level(target, dims, level, xoffset, yoffset, width, height);
  if (!level_ptr) return;
  TextureLevel& l = *level_ptr;
  const int b = l.border;
  if (width <= 0 || height <= 0) return;
  const int x0 = xoffset + b, y0 = dims == 2 ? yoffset + b : 0;
  if (l.format.base != GL_DEPTH_COMPONENT)
    return copy_color_texels(dims, x, y, source_width, source_height, l, x0, y0, width, height);
  std::vector<Rgba> unused;
  std::vector<double> depth;
  read_for_texture(true, dims, x, y, source_width, source_height, unused, depth);
  store_texels(l, x0, y0, width, height, unused, &depth);
}

void Context::glCopyTexSubImage1D(GLenum target, GLint level, GLint xoffset, GLint x, GLint y, GLsizei width) {
  PASSIM_ENTRY(target, level, xoffset, x, y, width)
  copy_tex_sub_image(target, 1, level, xoffset, 0, x, y, width, 1);
}

void Context::glCopyTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLint x, GLint y,
                                  GLsizei width, GLsizei height) {
  PASSIM_ENTRY(target, level, xoffset, yoffset, x, y, width, height)
  copy_tex_sub_image(target, 2, level, xoffset, yoffset, x, y, width, height);
}

std::uint64_t Context::tex_image_output_elements(GLenum target, GLint level, GLenum format, GLenum type) const {
  const TextureObject* tex = bound_texture(target);
  if (!tex || level < 0 || static_cast<std::size_t>(level) >= tex->levels.size()) return 0;
  const TextureLevel& l = tex->levels[static_cast<std::size_t>(level)];
  return l.defined() ? packed_image_elements(l.width, l.height, format, type, pixel_store_.pack) : 0;
}

void Context::glGetTexImage(GLenum target, GLint level, GLenum format, GLenum type, void* pixels) {
  PASSIM_ENTRY(target, level, format, type, pixels)
  TextureObject* tex = texture_for(target);
  if (!tex) return set_error(GL_INVALID_ENUM);
  if (!is_texture_format(format) || !is_pixel_type(type)) return set_error(GL_INVALID_ENUM);
  if (level < 0 || static_cast<std::size_t>(level) >= tex->levels.size() || !tex->levels[level].defined())
    return set_error(GL_INVALID_VALUE);
  const TextureLevel& l = tex->levels[static_cast<std::size_t>(level)];
  if ((format == GL_DEPTH_COMPONENT) != (l.format.base == GL_DEPTH_COMPONENT)) return set_error(GL_INVALID_OPERATION);
  // §6.1.4 (A13): no pixel transfer; texel components as RGBA (L in R, I in R, D in R). In
  // bands of rows (each packed as the image's rows from `first` on), so the scratch reals
  // are a band's, not the level's.
  constexpr int kBandRows = 32;
  // (Rows past what an int addresses cannot be packed: the size the spec's INVALID_VALUE is for.)
  if (pixel_store_.pack.skip_rows > std::numeric_limits<int>::max() - l.height) return set_error(GL_INVALID_VALUE);
  const InternalFormat& f = l.format;
  std::vector<Rgba> out;
  for (int first = 0; first < l.height; first += kBandRows) {
    const int rows = std::min(kBandRows, l.height - first);
    out.resize(static_cast<std::size_t>(l.width) * static_cast<std::size_t>(rows));
    const std::size_t texel0 = static_cast<std::size_t>(first) * static_cast<std::size_t>(l.width);
    for (std::size_t p = 0; p < out.size(); ++p) {
      double v[4];
      l.decode(texel0 + p, v);  // R G B A with L and I replicated, D in all four
      switch (f.base) {
        case GL_ALPHA: out[p] = {0, 0, 0, v[3]}; break;
        case GL_LUMINANCE: case GL_INTENSITY: case GL_DEPTH_COMPONENT: out[p] = {v[0], 0, 0, 1}; break;
        case GL_LUMINANCE_ALPHA: out[p] = {v[0], 0, 0, v[3]}; break;
        case GL_RGB: out[p] = {v[0], v[1], v[2], 1}; break;
        default: out[p] = {v[0], v[1], v[2], v[3]}; break;
      }
    }
    PixelStore band = pixel_store_.pack;
    band.skip_rows += first;
    pack_rgba(out, l.width, rows, format, type, band, pixels);
  }
}
// ---------------------------------------------------------------- parameters (§3.8.4)

void Context::set_tex_parameter(GLenum target, GLenum pname, const double* v) {
  TextureObject* tex = texture_for(target);
  if (!tex) return set_error(GL_INVALID_ENUM);
  const GLenum e = enum_param(v[0]);
  auto is_wrap = [](GLenum m) { return m == GL_REPEAT || m == GL_CLAMP || m == GL_CLAMP_TO_EDGE; };
  switch (pname) {
    case GL_TEXTURE_MIN_FILTER:
      if (e != GL_NEAREST && e != GL_LINEAR && e != GL_NEAREST_MIPMAP_NEAREST && e != GL_LINEAR_MIPMAP_NEAREST &&
          e != GL_NEAREST_MIPMAP_LINEAR && e != GL_LINEAR_MIPMAP_LINEAR)
        return set_error(GL_INVALID_ENUM);
      tex->min_filter = e;
      break;
    case GL_TEXTURE_MAG_FILTER:
      if (e != GL_NEAREST && e != GL_LINEAR) return set_error(GL_INVALID_ENUM);
      tex->mag_filter = e;
      break;
    case GL_TEXTURE_WRAP_S: case GL_TEXTURE_WRAP_T: case GL_TEXTURE_WRAP_R:
      if (!is_wrap(e)) return set_error(GL_INVALID_ENUM);
      (pname == GL_TEXTURE_WRAP_S ? tex->wrap_s : pname == GL_TEXTURE_WRAP_T ? tex->wrap_t : tex->wrap_r) = e;
      break;
    case GL_TEXTURE_BORDER_COLOR:
      tex->border_color = Vec4(clamp_nan_low(v[0], 0, 1), clamp_nan_low(v[1], 0, 1), clamp_nan_low(v[2], 0, 1),
                               clamp_nan_low(v[3], 0, 1));
      break;
    case GL_TEXTURE_MIN_LOD: tex->min_lod = v[0]; break;
    case GL_TEXTURE_MAX_LOD: tex->max_lod = v[0]; break;
    case GL_TEXTURE_BASE_LEVEL:
      if (v[0] < 0) return set_error(GL_INVALID_VALUE);
      tex->base_level = int_param(v[0]);
      break;
    case GL_TEXTURE_MAX_LEVEL:
      if (v[0] < 0) return set_error(GL_INVALID_VALUE);
      tex->max_level = int_param(v[0]);
      break;
    case GL_TEXTURE_PRIORITY: tex->priority = clamp_nan_low(v[0], 0, 1); break;
    case GL_TEXTURE_COMPARE_SGIX: tex->compare_sgix = v[0] != 0.0; break;
    case GL_TEXTURE_COMPARE_OPERATOR_SGIX:
      if (e != GL_TEXTURE_LEQUAL_R_SGIX && e != GL_TEXTURE_GEQUAL_R_SGIX) return set_error(GL_INVALID_ENUM);
      tex->compare_operator_sgix = e;
      break;
    case GL_SHADOW_AMBIENT_SGIX: tex->shadow_ambient = clamp_nan_low(v[0], 0, 1); break;
    case GL_TEXTURE_COMPARE_MODE:
      if (e != GL_NONE && e != GL_COMPARE_R_TO_TEXTURE) return set_error(GL_INVALID_ENUM);
      tex->compare_mode = e;
      break;
    case GL_TEXTURE_COMPARE_FUNC:
      if (e != GL_LEQUAL && e != GL_GEQUAL) return set_error(GL_INVALID_ENUM);
      tex->compare_func = e;
      break;
    case GL_DEPTH_TEXTURE_MODE:
      if (e != GL_LUMINANCE && e != GL_INTENSITY && e != GL_ALPHA) return set_error(GL_INVALID_ENUM);
      tex->depth_texture_mode = e;
      break;
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glTexParameteri(GLenum target, GLenum pname, GLint param) {
  PASSIM_ENTRY(target, pname, param)
  scalar_parameter(pname == GL_TEXTURE_BORDER_COLOR, param, [&](const double* v) {
    set_tex_parameter(target, pname, v);
  });
}

void Context::glTexParameterf(GLenum target, GLenum pname, GLfloat param) {
  PASSIM_ENTRY(target, pname, param)
  scalar_parameter(pname == GL_TEXTURE_BORDER_COLOR, param, [&](const double* v) {
    set_tex_parameter(target, pname, v);
  });
}

void Context::glTexParameterfv(GLenum target, GLenum pname, const GLfloat* params) {
  const int n = pname == GL_TEXTURE_BORDER_COLOR ? 4 : 1;
  PASSIM_ENTRY(target, pname, params)
  vector_parameter(params, n, [&](const double* v) { set_tex_parameter(target, pname, v); });
}

void Context::glGetTexParameterfv(GLenum target, GLenum pname, GLfloat* params) {
  PASSIM_ENTRY(target, pname, params)
  const TextureObject* tex = texture_for(target);
  if (!tex) return set_error(GL_INVALID_ENUM);
  switch (pname) {
    case GL_TEXTURE_MIN_FILTER: params[0] = static_cast<GLfloat>(tex->min_filter); break;
    case GL_TEXTURE_MAG_FILTER: params[0] = static_cast<GLfloat>(tex->mag_filter); break;
    case GL_TEXTURE_WRAP_S: params[0] = static_cast<GLfloat>(tex->wrap_s); break;
    case GL_TEXTURE_WRAP_T: params[0] = static_cast<GLfloat>(tex->wrap_t); break;
    case GL_TEXTURE_WRAP_R: params[0] = static_cast<GLfloat>(tex->wrap_r); break;
    case GL_TEXTURE_BORDER_COLOR:
      for (int k = 0; k < 4; ++k) params[k] = static_cast<GLfloat>(tex->border_color[k]);
      break;
    case GL_TEXTURE_MIN_LOD: params[0] = static_cast<GLfloat>(tex->min_lod); break;
    case GL_TEXTURE_MAX_LOD: params[0] = static_cast<GLfloat>(tex->max_lod); break;
    case GL_TEXTURE_BASE_LEVEL: params[0] = static_cast<GLfloat>(tex->base_level); break;
    case GL_TEXTURE_MAX_LEVEL: params[0] = static_cast<GLfloat>(tex->max_level); break;
    case GL_TEXTURE_PRIORITY: params[0] = static_cast<GLfloat>(tex->priority); break;
    case GL_TEXTURE_RESIDENT: params[0] = 1.0f; break;
    case GL_TEXTURE_COMPARE_SGIX: params[0] = tex->compare_sgix ? 1.0f : 0.0f; break;
    case GL_TEXTURE_COMPARE_OPERATOR_SGIX: params[0] = static_cast<GLfloat>(tex->compare_operator_sgix); break;
    case GL_SHADOW_AMBIENT_SGIX: params[0] = static_cast<GLfloat>(tex->shadow_ambient); break;
    case GL_TEXTURE_COMPARE_MODE: params[0] = static_cast<GLfloat>(tex->compare_mode); break;
    case GL_TEXTURE_COMPARE_FUNC: params[0] = static_cast<GLfloat>(tex->compare_func); break;
    case GL_DEPTH_TEXTURE_MODE: params[0] = static_cast<GLfloat>(tex->depth_texture_mode); break;
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glGetTexParameteriv(GLenum target, GLenum pname, GLint* params) {
  PASSIM_ENTRY(target, pname, params)
  GLfloat v[4] = {0, 0, 0, 0};
  const std::size_t errors = error_log_.size();
  glGetTexParameterfv(target, pname, v);
  if (error_log_.size() != errors) return;
  const int n = pname == GL_TEXTURE_BORDER_COLOR ? 4 : 1;
  for (int k = 0; k < n; ++k)
    // Saturated: a level of 2^31 − 1 comes back from float as 2^31 (found by fuzzing).
    params[k] = pname == GL_TEXTURE_BORDER_COLOR ? int_param(round_half_up(v[k] * 2147483647.0))
                                                 : int_param(round_half_up(v[k]));
}

void Context::glGetTexLevelParameteriv(GLenum target, GLint level, GLenum pname, GLint* params) {
  PASSIM_ENTRY(target, level, pname, params)
  const TextureObject* tex = texture_for(target);
  if (!tex) return set_error(GL_INVALID_ENUM);
  if (level < 0) return set_error(GL_INVALID_VALUE);
  TextureLevel empty;
  const TextureLevel& l = static_cast<std::size_t>(level) < tex->levels.size() ? tex->levels[level] : empty;
  const InternalFormat& f = l.format;
  switch (pname) {
    case GL_TEXTURE_WIDTH: params[0] = l.width; break;
    case GL_TEXTURE_HEIGHT: params[0] = l.height; break;
    case GL_TEXTURE_BORDER: params[0] = l.border; break;
    case GL_TEXTURE_INTERNAL_FORMAT: params[0] = l.defined() ? static_cast<GLint>(f.requested) : 1; break;
    case GL_TEXTURE_RED_SIZE: params[0] = f.red; break;
    case GL_TEXTURE_GREEN_SIZE: params[0] = f.green; break;
    case GL_TEXTURE_BLUE_SIZE: params[0] = f.blue; break;
    case GL_TEXTURE_ALPHA_SIZE: params[0] = f.alpha; break;
    case GL_TEXTURE_LUMINANCE_SIZE: params[0] = f.luminance; break;
    case GL_TEXTURE_INTENSITY_SIZE: params[0] = f.intensity; break;
    case GL_TEXTURE_DEPTH_SIZE: params[0] = f.depth; break;
    default: return set_error(GL_INVALID_ENUM);
  }
}

}  // namespace passim
