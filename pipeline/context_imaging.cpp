// Context: the imaging subset (ARB_imaging): colour tables, convolution filters, the
// histogram and minmax.
#include <algorithm>
#include <cstring>
#include <fmt/format.h>

#include "client/pixel_pack.hpp"
#include "pipeline/context.hpp"
#include "pipeline/fixed_point.hpp"
#include "pipeline/texture.hpp"

namespace passim {

namespace {
int table_index(GLenum target) {
  switch (target) {
    case GL_COLOR_TABLE: return kColorTable;
    case GL_POST_CONVOLUTION_COLOR_TABLE: return kPostConvolutionTable;
    case GL_POST_COLOR_MATRIX_COLOR_TABLE: return kPostColorMatrixTable;
    default: return -1;
  }
}
bool is_power_of_two_or_zero(int v) { return v >= 0 && (v & (v - 1)) == 0; }

// §6.1.4, Table 6.1: a table's or filter's components as the RGBA a query returns:
// luminance and intensity in R; components the base format lacks are 0 (R, G, B) or 1 (A).
Rgba returned_components(GLenum base, const Rgba& c) {
  switch (base) {
    case GL_ALPHA: return {0, 0, 0, c[3]};
    case GL_LUMINANCE: case GL_INTENSITY: return {c[0], 0, 0, 1};
    case GL_LUMINANCE_ALPHA: return {c[0], 0, 0, c[3]};
    case GL_RGB: return {c[0], c[1], c[2], 1};
    default: return c;
  }
}

// The formats and types a table or filter query may ask for.
bool is_query_image_format(GLenum format, GLenum type) {
  return format_components(format) != 0 && format != GL_DEPTH_COMPONENT && format != GL_STENCIL_INDEX &&
         format != GL_COLOR_INDEX && is_pixel_type(type);
}
}  // namespace

void Context::define_color_table(int index, GLenum internalformat, int width, int start, const std::vector<Rgba>& rgba) {
  ColorTable& t = transfer_.tables[static_cast<std::size_t>(index)];
  if (start < 0) {  // a whole new table
    t.internal_format = internalformat;
    t.base = internal_format(static_cast<GLint>(internalformat))->base;
    t.entries.assign(static_cast<std::size_t>(width), Rgba{0, 0, 0, 0});
    start = 0;
  }
  // §3.6.3: ×COLOR_TABLE_SCALE + COLOR_TABLE_BIAS, clamp to [0, 1]; the base format's
  // components are kept (L and I in [0]).
  for (int i = 0; i < width; ++i) {
    Rgba c = rgba[static_cast<std::size_t>(i)];
    for (int k = 0; k < 4; ++k)
      c[static_cast<std::size_t>(k)] = clamp_nan_low(c[static_cast<std::size_t>(k)] * t.scale[k] + t.bias[k], 0.0, 1.0);
    t.entries[static_cast<std::size_t>(start + i)] = c;
  }
}

bool Context::check_table_format(GLenum internalformat) {
  const auto f = internal_format(static_cast<GLint>(internalformat));
  if (!f || f->base == GL_DEPTH_COMPONENT || (internalformat >= 1 && internalformat <= 4)) {
    set_error(GL_INVALID_ENUM);
    return false;
  }
  return true;
}

void Context::glColorTable(GLenum target, GLenum internalformat, GLsizei width, GLenum format, GLenum type,
                           const void* table) {
  PASSIM_ENTRY(target, internalformat, width, format, type,
               table)
  const int index = table_index(target);
  if (index < 0) return set_error(GL_INVALID_ENUM);
  if (!check_table_format(internalformat)) return;
  if (format_components(format) == 0 || format == GL_DEPTH_COMPONENT || format == GL_STENCIL_INDEX ||
      format == GL_COLOR_INDEX || !is_pixel_type(type))
    return set_error(GL_INVALID_ENUM);
  if (!is_power_of_two_or_zero(width)) return set_error(GL_INVALID_VALUE);
  if (width > profile_.limits.max_color_table_width) return set_error(GL_TABLE_TOO_LARGE);
  std::vector<Rgba> rgba(static_cast<std::size_t>(width), Rgba{0, 0, 0, 1});
  // No pixel-transfer operations apply to the table's own definition.
  if (table && width > 0) unpack_rgba(table, width, 1, format, type, pixel_store_.unpack, rgba);
  define_color_table(index, internalformat, width, -1, rgba);
}

void Context::glColorSubTable(GLenum target, GLsizei start, GLsizei count, GLenum format, GLenum type,
                              const void* data) {
  PASSIM_ENTRY(target, start, count, format, type,
               data)
  const int index = table_index(target);
  if (index < 0) return set_error(GL_INVALID_ENUM);
  if (format_components(format) == 0 || format == GL_DEPTH_COMPONENT || !is_pixel_type(type))
    return set_error(GL_INVALID_ENUM);
  const ColorTable& t = transfer_.tables[static_cast<std::size_t>(index)];
  // A16: entries start .. start + count − 1 (the spec's "count + n" is a typo).
  if (start < 0 || count < 0 || static_cast<std::size_t>(start) + static_cast<std::size_t>(count) > t.entries.size())
    return set_error(GL_INVALID_VALUE);
  if (count == 0 || !data) return;
  std::vector<Rgba> rgba;
  unpack_rgba(data, count, 1, format, type, pixel_store_.unpack, rgba);
  define_color_table(index, t.internal_format, count, start, rgba);
}

void Context::glCopyColorTable(GLenum target, GLenum internalformat, GLint x, GLint y, GLsizei width) {
  PASSIM_ENTRY(target, internalformat, x, y, width)
  const int index = table_index(target);
  if (index < 0) return set_error(GL_INVALID_ENUM);
  if (!check_table_format(internalformat)) return;
  if (!is_power_of_two_or_zero(width)) return set_error(GL_INVALID_VALUE);
  if (width > profile_.limits.max_color_table_width) return set_error(GL_TABLE_TOO_LARGE);
  std::vector<Rgba> rgba;
  read_framebuffer_rgba(x, y, width, 1, rgba);
  counters().pixels_read += static_cast<std::uint64_t>(width);
  define_color_table(index, internalformat, width, -1, rgba);
}

void Context::glCopyColorSubTable(GLenum target, GLsizei start, GLint x, GLint y, GLsizei width) {
  PASSIM_ENTRY(target, start, x, y, width)
  const int index = table_index(target);
  if (index < 0) return set_error(GL_INVALID_ENUM);
  const ColorTable& t = transfer_.tables[static_cast<std::size_t>(index)];
  if (start < 0 || width < 0 || static_cast<std::size_t>(start) + static_cast<std::size_t>(width) > t.entries.size())
    return set_error(GL_INVALID_VALUE);
  if (width == 0) return;
  std::vector<Rgba> rgba;
  read_framebuffer_rgba(x, y, width, 1, rgba);
  counters().pixels_read += static_cast<std::uint64_t>(width);
  define_color_table(index, t.internal_format, width, start, rgba);
}

void Context::glGetColorTable(GLenum target, GLenum format, GLenum type, void* table) {
  PASSIM_ENTRY(target, format, type, table)
  const int index = table_index(target);
  if (index < 0 || !is_query_image_format(format, type)) return set_error(GL_INVALID_ENUM);
  const ColorTable& t = transfer_.tables[static_cast<std::size_t>(index)];
  std::vector<Rgba> out;
  for (const Rgba& e : t.entries) out.push_back(returned_components(t.base, e));
  if (!out.empty()) pack_rgba(out, static_cast<int>(out.size()), 1, format, type, pixel_store_.pack, table);
}

void Context::glColorTableParameterfv(GLenum target, GLenum pname, const GLfloat* params) {
  PASSIM_ENTRY(target, pname, params)
  const int index = table_index(target);
  if (index < 0) return set_error(GL_INVALID_ENUM);
  ColorTable& t = transfer_.tables[static_cast<std::size_t>(index)];
  const Vec4 v(params[0], params[1], params[2], params[3]);
  if (pname == GL_COLOR_TABLE_SCALE) t.scale = v;
  else if (pname == GL_COLOR_TABLE_BIAS) t.bias = v;
  else set_error(GL_INVALID_ENUM);
}

void Context::glGetColorTableParameteriv(GLenum target, GLenum pname, GLint* params) {
  PASSIM_ENTRY(target, pname, params)
  const int index = table_index(target);
  if (index < 0) return set_error(GL_INVALID_ENUM);
  const ColorTable& t = transfer_.tables[static_cast<std::size_t>(index)];
  const auto f = internal_format(static_cast<GLint>(t.internal_format));
  switch (pname) {
    case GL_COLOR_TABLE_WIDTH: params[0] = static_cast<GLint>(t.entries.size()); break;
    case GL_COLOR_TABLE_FORMAT: params[0] = static_cast<GLint>(t.internal_format); break;
    // A24: the sizes reported are those of the requested format (the table itself is kept as reals).
    case GL_COLOR_TABLE_RED_SIZE: params[0] = f->red; break;
    case GL_COLOR_TABLE_GREEN_SIZE: params[0] = f->green; break;
    case GL_COLOR_TABLE_BLUE_SIZE: params[0] = f->blue; break;
    case GL_COLOR_TABLE_ALPHA_SIZE: params[0] = f->alpha; break;
    case GL_COLOR_TABLE_LUMINANCE_SIZE: params[0] = f->luminance; break;
    case GL_COLOR_TABLE_INTENSITY_SIZE: params[0] = f->intensity; break;
    // Table 6.18's scale and bias (attribute "pixel"), rounded to integers (§6.1.2).
    case GL_COLOR_TABLE_SCALE: case GL_COLOR_TABLE_BIAS: {
      const Vec4& v = pname == GL_COLOR_TABLE_SCALE ? t.scale : t.bias;
      for (int k = 0; k < 4; ++k)
        params[k] = static_cast<GLint>(std::clamp(round_half_up(v[k]), -2147483648.0, 2147483647.0));
      break;
    }
    default: return set_error(GL_INVALID_ENUM);
  }
}

}  // namespace passim

namespace passim {
// ---------------------------------------------------------------- convolution filters

ConvolutionFilter* Context::filter_for(GLenum target) {
  switch (target) {
    case GL_CONVOLUTION_1D: return &transfer_.filter_1d;
    case GL_CONVOLUTION_2D: return &transfer_.filter_2d;
    case GL_SEPARABLE_2D: return &transfer_.filter_separable;
    default: return nullptr;
  }
}

bool Context::check_filter_format(GLenum internalformat, GLenum format, GLenum type) {
  const auto f = internal_format(static_cast<GLint>(internalformat));
  if (!f || f->base == GL_DEPTH_COMPONENT || (internalformat >= 1 && internalformat <= 4) ||
      format_components(format) == 0 || format == GL_DEPTH_COMPONENT || format == GL_STENCIL_INDEX ||
      format == GL_COLOR_INDEX || !is_pixel_type(type)) {
    set_error(GL_INVALID_ENUM);
    return false;
  }
  return true;
}

void Context::define_filter(ConvolutionFilter& f, GLenum internalformat, int width, int height,
                            std::vector<Rgba>&& taps) {
  // §3.6.3: ×FILTER_SCALE + FILTER_BIAS, no clamp; the base format's components are used.
  for (Rgba& t : taps)
    for (int k = 0; k < 4; ++k) t[static_cast<std::size_t>(k)] = t[static_cast<std::size_t>(k)] * f.scale[k] + f.bias[k];
  f.internal_format = internalformat;
  f.base = internal_format(static_cast<GLint>(internalformat))->base;
  f.width = width;
  f.height = height;
  f.separable = false;
  f.taps = std::move(taps);
}

void Context::glConvolutionFilter1D(GLenum target, GLenum internalformat, GLsizei width, GLenum format, GLenum type,
                                    const void* image) {
  PASSIM_ENTRY(target, internalformat, width, format, type,
               image)
  if (target != GL_CONVOLUTION_1D) return set_error(GL_INVALID_ENUM);
  if (!check_filter_format(internalformat, format, type)) return;
  if (width < 0 || width > profile_.limits.max_convolution_width) return set_error(GL_INVALID_VALUE);
  std::vector<Rgba> taps(static_cast<std::size_t>(width), Rgba{0, 0, 0, 1});
  if (image && width > 0) unpack_rgba(image, width, 1, format, type, pixel_store_.unpack, taps);
  define_filter(transfer_.filter_1d, internalformat, width, 1, std::move(taps));
}

void Context::glConvolutionFilter2D(GLenum target, GLenum internalformat, GLsizei width, GLsizei height,
                                    GLenum format, GLenum type, const void* image) {
  PASSIM_ENTRY(target, internalformat, width, height, format, type,
               image)
  if (target != GL_CONVOLUTION_2D) return set_error(GL_INVALID_ENUM);
  if (!check_filter_format(internalformat, format, type)) return;
  if (width < 0 || height < 0 || width > profile_.limits.max_convolution_width ||
      height > profile_.limits.max_convolution_height)
    return set_error(GL_INVALID_VALUE);
  std::vector<Rgba> taps(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), Rgba{0, 0, 0, 1});
  if (image && width > 0 && height > 0) unpack_rgba(image, width, height, format, type, pixel_store_.unpack, taps);
  define_filter(transfer_.filter_2d, internalformat, width, height, std::move(taps));
}

void Context::glSeparableFilter2D(GLenum target, GLenum internalformat, GLsizei width, GLsizei height, GLenum format,
                                  GLenum type, const void* row, const void* column) {
  PASSIM_ENTRY(target, internalformat, width, height, format, type, row,
               column)
  if (target != GL_SEPARABLE_2D) return set_error(GL_INVALID_ENUM);
  if (!check_filter_format(internalformat, format, type)) return;
  if (width < 0 || height < 0 || width > profile_.limits.max_convolution_width ||
      height > profile_.limits.max_convolution_height)
    return set_error(GL_INVALID_VALUE);
  ConvolutionFilter& f = transfer_.filter_separable;
  std::vector<Rgba> r(static_cast<std::size_t>(width), Rgba{0, 0, 0, 1}), c(static_cast<std::size_t>(height), Rgba{0, 0, 0, 1});
  if (row && width > 0) unpack_rgba(row, width, 1, format, type, pixel_store_.unpack, r);
  if (column && height > 0) unpack_rgba(column, height, 1, format, type, pixel_store_.unpack, c);
  for (auto* v : {&r, &c})
    for (Rgba& t : *v)
      for (int k = 0; k < 4; ++k) t[static_cast<std::size_t>(k)] = t[static_cast<std::size_t>(k)] * f.scale[k] + f.bias[k];
  f.internal_format = internalformat;
  f.base = internal_format(static_cast<GLint>(internalformat))->base;
  f.width = width;
  f.height = height;
  f.separable = true;
  f.row = std::move(r);
  f.column = std::move(c);
}

void Context::glCopyConvolutionFilter2D(GLenum target, GLenum internalformat, GLint x, GLint y, GLsizei width,
                                        GLsizei height) {
  PASSIM_ENTRY(target, internalformat, x, y, width, height)
  if (target != GL_CONVOLUTION_2D) return set_error(GL_INVALID_ENUM);
  if (!check_filter_format(internalformat, GL_RGBA, GL_FLOAT)) return;
  if (width < 0 || height < 0 || width > profile_.limits.max_convolution_width ||
      height > profile_.limits.max_convolution_height)
    return set_error(GL_INVALID_VALUE);
  std::vector<Rgba> taps;
  read_framebuffer_rgba(x, y, width, height, taps);
  define_filter(transfer_.filter_2d, internalformat, width, height, std::move(taps));
}

void Context::glCopyConvolutionFilter1D(GLenum target, GLenum internalformat, GLint x, GLint y, GLsizei width) {
  PASSIM_ENTRY(target, internalformat, x, y, width)
  if (target != GL_CONVOLUTION_1D) return set_error(GL_INVALID_ENUM);
  if (!check_filter_format(internalformat, GL_RGBA, GL_FLOAT)) return;
  if (width < 0 || width > profile_.limits.max_convolution_width) return set_error(GL_INVALID_VALUE);
  std::vector<Rgba> taps;
  read_framebuffer_rgba(x, y, width, 1, taps);
  define_filter(transfer_.filter_1d, internalformat, width, 1, std::move(taps));
}

void Context::glGetConvolutionFilter(GLenum target, GLenum format, GLenum type, void* image) {
  PASSIM_ENTRY(target, format, type, image)
  const ConvolutionFilter* f = target == GL_CONVOLUTION_1D   ? &transfer_.filter_1d
                               : target == GL_CONVOLUTION_2D ? &transfer_.filter_2d
                                                             : nullptr;
  if (!f || !is_query_image_format(format, type)) return set_error(GL_INVALID_ENUM);
  std::vector<Rgba> out;
  for (const Rgba& t : f->taps) out.push_back(returned_components(f->base, t));
  if (!out.empty()) pack_rgba(out, f->width, f->height, format, type, pixel_store_.pack, image);
}

void Context::glGetSeparableFilter(GLenum target, GLenum format, GLenum type, void* row, void* column, void* span) {
  PASSIM_ENTRY(target, format, type, row, column, span)
  (void)span;  // unused by GL 1.2 (ARB_imaging)
  if (target != GL_SEPARABLE_2D || !is_query_image_format(format, type)) return set_error(GL_INVALID_ENUM);
  const ConvolutionFilter& f = transfer_.filter_separable;
  for (const auto& [taps, out] : {std::pair{&f.row, row}, std::pair{&f.column, column}}) {
    std::vector<Rgba> image;
    for (const Rgba& t : *taps) image.push_back(returned_components(f.base, t));
    if (!image.empty()) pack_rgba(image, static_cast<int>(image.size()), 1, format, type, pixel_store_.pack, out);
  }
}

void Context::set_convolution_parameter(GLenum target, GLenum pname, const double* v) {
  ConvolutionFilter* f = filter_for(target);
  if (!f) return set_error(GL_INVALID_ENUM);
  switch (pname) {
    case GL_CONVOLUTION_BORDER_MODE: {
      const GLenum m = enum_param(v[0]);
      if (m != GL_REDUCE && m != GL_CONSTANT_BORDER && m != GL_REPLICATE_BORDER) return set_error(GL_INVALID_ENUM);
      f->border_mode = m;
      break;
    }
    case GL_CONVOLUTION_BORDER_COLOR: f->border_color = Vec4(v[0], v[1], v[2], v[3]); break;  // not clamped
    case GL_CONVOLUTION_FILTER_SCALE: f->scale = Vec4(v[0], v[1], v[2], v[3]); break;
    case GL_CONVOLUTION_FILTER_BIAS: f->bias = Vec4(v[0], v[1], v[2], v[3]); break;
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glConvolutionParameteri(GLenum target, GLenum pname, GLint param) {
  PASSIM_ENTRY(target, pname, param)
  scalar_parameter(pname != GL_CONVOLUTION_BORDER_MODE, param, [&](const double* v) {
    set_convolution_parameter(target, pname, v);
  });
}

void Context::glConvolutionParameterfv(GLenum target, GLenum pname, const GLfloat* params) {
  const int n = pname == GL_CONVOLUTION_BORDER_MODE ? 1 : 4;
  PASSIM_ENTRY(target, pname, params)
  vector_parameter(params, n, [&](const double* v) { set_convolution_parameter(target, pname, v); });
}

}  // namespace passim

namespace passim {
// ---------------------------------------------------------------- histogram and minmax

namespace {
bool is_statistics_format(GLenum f) {
  const auto info = internal_format(static_cast<GLint>(f));
  // Histogram and minmax formats: no 1-4, no INTENSITY, no depth.
  return info && !(f >= 1 && f <= 4) && info->base != GL_INTENSITY && info->base != GL_DEPTH_COMPONENT;
}
}  // namespace

void Context::glHistogram(GLenum target, GLsizei width, GLenum internalformat, GLboolean sink) {
  PASSIM_ENTRY(target, width, internalformat, sink)
  if (target != GL_HISTOGRAM) return set_error(GL_INVALID_ENUM);
  if (width < 0 || (width & (width - 1)) != 0) return set_error(GL_INVALID_VALUE);
  if (!is_statistics_format(internalformat)) return set_error(GL_INVALID_ENUM);
  if (width > profile_.limits.max_histogram_width) return set_error(GL_TABLE_TOO_LARGE);
  Histogram& h = transfer_.histogram;
  h.internal_format = internalformat;
  h.base = internal_format(static_cast<GLint>(internalformat))->base;
  h.sink = sink != GL_FALSE;
  h.counts.assign(static_cast<std::size_t>(width), {0, 0, 0, 0});
}

void Context::glResetHistogram(GLenum target) {
  PASSIM_ENTRY(target)
  if (target != GL_HISTOGRAM) return set_error(GL_INVALID_ENUM);
  for (auto& c : transfer_.histogram.counts) c = {0, 0, 0, 0};
}

void Context::glGetHistogram(GLenum target, GLboolean reset, GLenum format, GLenum type, void* values) {
  PASSIM_ENTRY(target, reset, format, type, values)
  if (target != GL_HISTOGRAM) return set_error(GL_INVALID_ENUM);
  if (format_components(format) == 0 || format == GL_DEPTH_COMPONENT || !is_pixel_type(type))
    return set_error(GL_INVALID_ENUM);
  // Counts are returned as they are (no normalisation), converted to the type, in the
  // format's components (L from the red count).
  const int n = format_components(format), size = type_size(type);
  std::byte* out = static_cast<std::byte*>(values);
  for (std::size_t i = 0; i < transfer_.histogram.counts.size(); ++i) {
    const auto& c = transfer_.histogram.counts[i];
    std::uint32_t v[4] = {0, 0, 0, 0};
    switch (format) {
      case GL_RED: case GL_LUMINANCE: v[0] = c[0]; break;
      case GL_GREEN: v[0] = c[1]; break;
      case GL_BLUE: v[0] = c[2]; break;
      case GL_ALPHA: v[0] = c[3]; break;
      case GL_LUMINANCE_ALPHA: v[0] = c[0]; v[1] = c[3]; break;
      default: v[0] = c[0]; v[1] = c[1]; v[2] = c[2]; v[3] = c[3]; break;
    }
    for (int k = 0; k < n; ++k) {
      std::byte* p = out + (i * static_cast<std::size_t>(n) + static_cast<std::size_t>(k)) * static_cast<std::size_t>(size);
      auto put = [&](auto x) { std::memcpy(p, &x, sizeof(x)); };
      switch (type) {
        case GL_FLOAT: put(static_cast<float>(v[k])); break;
        case GL_UNSIGNED_BYTE: put(static_cast<std::uint8_t>(std::min<std::uint32_t>(v[k], 255))); break;
        case GL_BYTE: put(static_cast<std::int8_t>(std::min<std::uint32_t>(v[k], 127))); break;
        case GL_UNSIGNED_SHORT: put(static_cast<std::uint16_t>(std::min<std::uint32_t>(v[k], 65535))); break;
        case GL_SHORT: put(static_cast<std::int16_t>(std::min<std::uint32_t>(v[k], 32767))); break;
        case GL_INT: put(static_cast<std::int32_t>(std::min<std::uint32_t>(v[k], 2147483647u))); break;
        default: put(v[k]); break;
      }
    }
  }
  if (reset) glResetHistogram(GL_HISTOGRAM);
}

void Context::glMinmax(GLenum target, GLenum internalformat, GLboolean sink) {
  PASSIM_ENTRY(target, internalformat, sink)
  if (target != GL_MINMAX) return set_error(GL_INVALID_ENUM);
  if (!is_statistics_format(internalformat)) return set_error(GL_INVALID_ENUM);
  Minmax& m = transfer_.minmax;
  m.internal_format = internalformat;
  m.base = internal_format(static_cast<GLint>(internalformat))->base;
  m.sink = sink != GL_FALSE;
  m.reset();
}

void Context::glResetMinmax(GLenum target) {
  PASSIM_ENTRY(target)
  if (target != GL_MINMAX) return set_error(GL_INVALID_ENUM);
  transfer_.minmax.reset();
}

void Context::glGetMinmax(GLenum target, GLboolean reset, GLenum format, GLenum type, void* values) {
  PASSIM_ENTRY(target, reset, format, type, values)
  if (target != GL_MINMAX) return set_error(GL_INVALID_ENUM);
  if (format_components(format) == 0 || format == GL_DEPTH_COMPONENT || !is_pixel_type(type))
    return set_error(GL_INVALID_ENUM);
  // Two groups, minimum then maximum, packed like pixels (Table 4.7; FLOAT is not clamped
  // here so that the unclamped extremes can be read).
  const Minmax& m = transfer_.minmax;
  if (type == GL_FLOAT) {
    const int n = format_components(format);
    float* out = static_cast<float*>(values);
    for (int g = 0; g < 2; ++g) {
      const Rgba& v = g == 0 ? m.min : m.max;
      const double c[4] = {v[0], v[1], v[2], v[3]};
      for (int k = 0; k < n; ++k) {
        int src = k;
        if (format == GL_ALPHA) src = 3;
        else if (format == GL_GREEN) src = 1;
        else if (format == GL_BLUE) src = 2;
        else if (format == GL_LUMINANCE_ALPHA && k == 1) src = 3;
        out[g * n + k] = static_cast<float>(c[src]);
      }
    }
  } else {
    pack_rgba({m.min, m.max}, 2, 1, format, type, PixelStore{false, false, 0, 0, 0, 1}, values);
  }
  if (reset) glResetMinmax(GL_MINMAX);
}


// ---------------------------------------------------------------- what the queries write

std::uint64_t Context::color_table_output_elements(GLenum target, GLenum format, GLenum type) const {
  const int index = table_index(target);
  if (index < 0) return 0;
  const auto& entries = transfer_.tables[static_cast<std::size_t>(index)].entries;
  return packed_image_elements(static_cast<int>(entries.size()), 1, format, type, pixel_store_.pack);
}

std::uint64_t Context::filter_output_elements(GLenum target, GLenum format, GLenum type, int part) const {
  if (part == 0) {
    const ConvolutionFilter* f = target == GL_CONVOLUTION_1D   ? &transfer_.filter_1d
                                 : target == GL_CONVOLUTION_2D ? &transfer_.filter_2d
                                                               : nullptr;
    return f ? packed_image_elements(f->width, f->height, format, type, pixel_store_.pack) : 0;
  }
  if (target != GL_SEPARABLE_2D) return 0;
  const ConvolutionFilter& f = transfer_.filter_separable;
  return packed_image_elements(static_cast<int>((part == 1 ? f.row : f.column).size()), 1, format, type, pixel_store_.pack);
}

std::uint64_t Context::histogram_output_elements(GLenum format, GLenum type) const {
  // glGetHistogram writes the counts contiguously, a group per entry.
  if (!is_pixel_type(type)) return 0;
  return transfer_.histogram.counts.size() * static_cast<std::uint64_t>(format_components(format));
}

std::uint64_t Context::minmax_output_elements(GLenum format, GLenum type) const {
  // Two groups: the minimum, then the maximum.
  if (!is_pixel_type(type)) return 0;
  return 2 * static_cast<std::uint64_t>(format_components(format));
}

}  // namespace passim
