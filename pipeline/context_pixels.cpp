// Context: pixel storage (§3.6.1), the raster position (§2.12), pixel maps and transfer
// (§3.6.3), and pixel rectangles: DrawPixels, ReadPixels, CopyPixels, Bitmap (§3.6-3.7, §4.3).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <fmt/format.h>

#include "client/glu_mipmaps.hpp"
#include "client/pixel_pack.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/clipping.hpp"
#include "stages/kernel_paths.hpp"
#include "stages/pixel_transfer.hpp"
#include "stages/texture_sample.hpp"

namespace passim {

// ---------------------------------------------------------------- pixel storage

void Context::glPixelStorei(GLenum pname, GLint param) {
  PASSIM_ENTRY(pname, param)
  PixelStore* s = nullptr;
  switch (pname) {
    case GL_PACK_SWAP_BYTES: case GL_PACK_LSB_FIRST: case GL_PACK_ROW_LENGTH: case GL_PACK_SKIP_ROWS:
    case GL_PACK_SKIP_PIXELS: case GL_PACK_ALIGNMENT: s = &pixel_store_.pack; break;
    case GL_UNPACK_SWAP_BYTES: case GL_UNPACK_LSB_FIRST: case GL_UNPACK_ROW_LENGTH: case GL_UNPACK_SKIP_ROWS:
    case GL_UNPACK_SKIP_PIXELS: case GL_UNPACK_ALIGNMENT: s = &pixel_store_.unpack; break;
    default: return set_error(GL_INVALID_ENUM);
  }
  switch (pname) {
    case GL_PACK_SWAP_BYTES: case GL_UNPACK_SWAP_BYTES: s->swap_bytes = param != 0; break;
    case GL_PACK_LSB_FIRST: case GL_UNPACK_LSB_FIRST: s->lsb_first = param != 0; break;
    case GL_PACK_ALIGNMENT: case GL_UNPACK_ALIGNMENT:
      if (param != 1 && param != 2 && param != 4 && param != 8) return set_error(GL_INVALID_VALUE);
      s->alignment = param;
      break;
    default:
      if (param < 0) return set_error(GL_INVALID_VALUE);
      if (pname == GL_PACK_ROW_LENGTH || pname == GL_UNPACK_ROW_LENGTH) s->row_length = param;
      else if (pname == GL_PACK_SKIP_ROWS || pname == GL_UNPACK_SKIP_ROWS) s->skip_rows = param;
      else s->skip_pixels = param;
      break;
  }
}

void Context::glPixelStoref(GLenum pname, GLfloat param) {
  PASSIM_ENTRY(pname, param)
  // §3.6.1: a float parameter is rounded to the nearest integer (booleans: nonzero is true).
  glPixelStorei(pname, static_cast<GLint>(round_half_up(clamp_nan_low(param, -2147483648.0, 2147483647.0))));
}

// ---------------------------------------------------------------- raster position (§2.12)

void Context::set_raster_position(const Vec4& object) {
  Counters& c = counters();
  ProcessedVertex v = process_vertex(object, c);
  ClipPlanes planes;
  planes.user = transform_.clip_plane;
  for (int k = 0; k < 6; ++k)
    if (transform_.clip_enabled[k]) planes.user_enabled |= 1u << k;
  const bool finite = std::isfinite(v.clip.x) && std::isfinite(v.clip.y) && std::isfinite(v.clip.z) &&
                      std::isfinite(v.clip.w);
  // Clipped as a point: outside the clip volume the raster position becomes invalid.
  if (!finite || !point_inside(v, planes)) {
    raster_.valid = false;
    return;
  }
  if (v.light_pending) light_pending_vertex(v, 0);
  raster_.window = to_window(v, 0);
  raster_.valid = raster_.window.finite_position();  // w = 0 on the boundary: no position
  raster_.color = v.color[0];
}

void Context::glRasterPos2i(GLint x, GLint y) { PASSIM_ENTRY(x, y) set_raster_position(Vec4(x, y, 0.0, 1.0)); }
void Context::glRasterPos2f(GLfloat x, GLfloat y) { PASSIM_ENTRY(x, y) set_raster_position(Vec4(x, y, 0.0, 1.0)); }
void Context::glRasterPos3f(GLfloat x, GLfloat y, GLfloat z) { PASSIM_ENTRY(x, y, z) set_raster_position(Vec4(x, y, z, 1.0)); }
void Context::glRasterPos4f(GLfloat x, GLfloat y, GLfloat z, GLfloat w) { PASSIM_ENTRY(x, y, z, w) set_raster_position(Vec4(x, y, z, w)); }
void Context::glRasterPos2d(GLdouble x, GLdouble y) { PASSIM_ENTRY(x, y) set_raster_position(Vec4(x, y, 0.0, 1.0)); }
void Context::glRasterPos3d(GLdouble x, GLdouble y, GLdouble z) { PASSIM_ENTRY(x, y, z) set_raster_position(Vec4(x, y, z, 1.0)); }

void Context::glPixelZoom(GLfloat xfactor, GLfloat yfactor) {
  PASSIM_ENTRY(xfactor, yfactor)
  zoom_x_ = xfactor;
  zoom_y_ = yfactor;
}

void Context::glPixelTransferf(GLenum pname, GLfloat param) {
  PASSIM_ENTRY(pname, param)
  PixelTransferState& t = transfer_;
  const double v = param;
  switch (pname) {
    case GL_RED_SCALE: t.scale.r = v; break;
    case GL_GREEN_SCALE: t.scale.g = v; break;
    case GL_BLUE_SCALE: t.scale.b = v; break;
    case GL_ALPHA_SCALE: t.scale.a = v; break;
    case GL_RED_BIAS: t.bias.r = v; break;
    case GL_GREEN_BIAS: t.bias.g = v; break;
    case GL_BLUE_BIAS: t.bias.b = v; break;
    case GL_ALPHA_BIAS: t.bias.a = v; break;
    case GL_DEPTH_SCALE: t.depth_scale = v; break;
    case GL_DEPTH_BIAS: t.depth_bias = v; break;
    case GL_POST_COLOR_MATRIX_RED_SCALE: t.post_color_matrix_scale.r = v; break;
    case GL_POST_COLOR_MATRIX_GREEN_SCALE: t.post_color_matrix_scale.g = v; break;
    case GL_POST_COLOR_MATRIX_BLUE_SCALE: t.post_color_matrix_scale.b = v; break;
    case GL_POST_COLOR_MATRIX_ALPHA_SCALE: t.post_color_matrix_scale.a = v; break;
    case GL_POST_COLOR_MATRIX_RED_BIAS: t.post_color_matrix_bias.r = v; break;
    case GL_POST_COLOR_MATRIX_GREEN_BIAS: t.post_color_matrix_bias.g = v; break;
    case GL_POST_COLOR_MATRIX_BLUE_BIAS: t.post_color_matrix_bias.b = v; break;
    case GL_POST_COLOR_MATRIX_ALPHA_BIAS: t.post_color_matrix_bias.a = v; break;
    case GL_POST_CONVOLUTION_RED_SCALE: t.post_convolution_scale.r = v; break;
    case GL_POST_CONVOLUTION_GREEN_SCALE: t.post_convolution_scale.g = v; break;
    case GL_POST_CONVOLUTION_BLUE_SCALE: t.post_convolution_scale.b = v; break;
    case GL_POST_CONVOLUTION_ALPHA_SCALE: t.post_convolution_scale.a = v; break;
    case GL_POST_CONVOLUTION_RED_BIAS: t.post_convolution_bias.r = v; break;
    case GL_POST_CONVOLUTION_GREEN_BIAS: t.post_convolution_bias.g = v; break;
    case GL_POST_CONVOLUTION_BLUE_BIAS: t.post_convolution_bias.b = v; break;
    case GL_POST_CONVOLUTION_ALPHA_BIAS: t.post_convolution_bias.a = v; break;
    case GL_MAP_COLOR: t.map_color = v != 0.0; break;
    case GL_MAP_STENCIL: t.map_stencil = v != 0.0; break;
    case GL_INDEX_SHIFT: t.index_shift = int_param(v); break;
    case GL_INDEX_OFFSET: t.index_offset = int_param(v); break;
    default: return set_error(GL_INVALID_ENUM);
  }
}

void Context::glPixelTransferi(GLenum pname, GLint param) {
  PASSIM_ENTRY(pname, param)
  // The index parameters are integers: kept exactly (a float would round 2^24 + 1).
  if (pname == GL_INDEX_SHIFT) transfer_.index_shift = param;
  else if (pname == GL_INDEX_OFFSET) transfer_.index_offset = param;
  else glPixelTransferf(pname, static_cast<GLfloat>(param));
}
// ---------------------------------------------------------------- pixel maps (§3.6.3)

void Context::set_pixel_map(GLenum map, GLsizei mapsize, const double* values) {
  const bool is_color = map >= GL_PIXEL_MAP_R_TO_R && map <= GL_PIXEL_MAP_A_TO_A;
  const bool is_index = map >= GL_PIXEL_MAP_I_TO_I && map <= GL_PIXEL_MAP_I_TO_A;
  if (!is_color && !is_index) return set_error(GL_INVALID_ENUM);
  if (mapsize < 1 || mapsize > profile_.limits.max_pixel_map_table) return set_error(GL_INVALID_VALUE);
  // I_TO_* and S_TO_S maps must be a power of two in size.
  if (!is_color && (mapsize & (mapsize - 1)) != 0) return set_error(GL_INVALID_VALUE);
  std::vector<double> entries(static_cast<std::size_t>(mapsize));
  for (GLsizei k = 0; k < mapsize; ++k)
    entries[static_cast<std::size_t>(k)] = is_color ? clamp_nan_low(values[k], 0.0, 1.0) : values[k];  // A19
  if (is_color) transfer_.color_maps[map - GL_PIXEL_MAP_R_TO_R] = std::move(entries);
  else transfer_.other_maps[map - GL_PIXEL_MAP_I_TO_I] = std::move(entries);
  if (map == GL_PIXEL_MAP_I_TO_I || map == GL_PIXEL_MAP_S_TO_S || (map >= GL_PIXEL_MAP_I_TO_R && map <= GL_PIXEL_MAP_I_TO_A))
    warn_once("index pixel maps are stored, but colour-index and stencil rectangles are not modelled yet");
}

void Context::glPixelMapfv(GLenum map, GLsizei mapsize, const GLfloat* values) {
  PASSIM_ENTRY(map, mapsize, values)
  std::vector<double> v(mapsize > 0 ? static_cast<std::size_t>(mapsize) : 0u);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = values[k];
  set_pixel_map(map, mapsize, v.data());
}

namespace {

// Colour maps given as integers are normalised (Table 2.6: c / (2^b − 1)); index maps keep
// the integer.
template <class T>
std::vector<double> pixel_map_values(GLenum map, GLsizei mapsize, const T* values, double max_value) {
  const bool is_color = map >= GL_PIXEL_MAP_R_TO_R && map <= GL_PIXEL_MAP_A_TO_A;
  std::vector<double> v(mapsize > 0 && values ? static_cast<std::size_t>(mapsize) : 0u);
  for (std::size_t k = 0; k < v.size(); ++k)
    v[k] = is_color ? static_cast<double>(values[k]) / max_value : static_cast<double>(values[k]);
  return v;
}

}  // namespace

void Context::glPixelMapusv(GLenum map, GLsizei mapsize, const GLushort* values) {
  PASSIM_ENTRY(map, mapsize, values)
  set_pixel_map(map, mapsize, pixel_map_values(map, mapsize, values, 65535.0).data());
}

void Context::glPixelMapuiv(GLenum map, GLsizei mapsize, const GLuint* values) {
  PASSIM_ENTRY(map, mapsize, values)
  set_pixel_map(map, mapsize, pixel_map_values(map, mapsize, values, 4294967295.0).data());
}
// ---------------------------------------------------------------- rectangles to fragments (§3.6.4)

Context::RasterFragments Context::raster_fragments(const TriangleOptions& options) const {
  // §3.6.4, §3.7: pixel-rectangle and bitmap fragments take the raster position's colour,
  // window z, texture coordinates and eye distance (for fog).
  RasterFragments f;
  const RasterVertex& rp = raster_.window;
  f.z = fb_.config.depth_bits ? float_to_fixed(rp.z, fb_.config.depth_bits) : 0;
  for (int k = 0; k < 4; ++k) f.codes[k] = static_cast<std::uint16_t>(float_to_fixed(raster_.color[k], fragment_bits_[k]));
  f.s = rp.tex[0] / rp.tex[3];
  f.t = rp.tex[1] / rp.tex[3];
  f.r = rp.tex[2] / rp.tex[3];
  f.fog = std::fabs(rp.eye_z);
  f.extras = options.texcoords || options.fog;  // written only when a stage reads them
  return f;
}

void Context::RasterFragments::put(FragmentSpan& span, int first, int count, bool colour, bool depth) const {
  const int end = first + count;
  if (colour)
    for (int i = first; i < end; ++i)
      for (int k = 0; k < 4; ++k) span.rgba[4 * i + k] = codes[k];
  if (depth) std::fill(span.depth + first, span.depth + end, z);
  if (!extras) return;
  std::fill(span.s + first, span.s + end, s);
  std::fill(span.t + first, span.t + end, t);
  std::fill(span.r + first, span.r + end, r);
  std::fill(span.lambda + first, span.lambda + end, 0.0);  // ρ = 1 for pixel rectangles and bitmaps
  std::fill(span.fog + first, span.fog + end, fog);
}

void Context::glBitmap(GLsizei width, GLsizei height, GLfloat xorig, GLfloat yorig, GLfloat xmove, GLfloat ymove,
                       const GLubyte* bitmap) {
  PASSIM_ENTRY(width, height, xorig, yorig, xmove, ymove,
               bitmap)
  if (width < 0 || height < 0) return set_error(GL_INVALID_VALUE);
  if (!raster_.valid) return;  // §3.7: an invalid raster position ignores the bitmap and stays
  if (bitmap && width > 0 && height > 0) {
    Counters& c = counters();
    c.pixels_drawn += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    TriangleOptions options;
    prepare_fragment_stages(options);
    FragmentSink& sink = fragment_sink();
    const RasterFragments raster = raster_fragments(options);
    // x_ll = ⌊x_rp − x_o⌋, y_ll = ⌊y_rp − y_o⌋; bit (i, j) is the fragment (x_ll + i, y_ll + j).
    const double xll = std::floor(raster_.window.x - xorig), yll = std::floor(raster_.window.y - yorig);
    SpanBuffers& buf = scratch_->spans;
    for (int j = 0; j < height; ++j) {
      const double y = yll + j;
      if (y < 0 || y >= fb_.height()) continue;
      FragmentSpan span = buf.span(static_cast<int>(y), 0, 0);
      int count = 0, x_first = 0;
      auto flush = [&] {
        if (count == 0) return;
        span.x0 = x_first;
        span.count = count;
        c.fragments_generated += static_cast<std::uint64_t>(count);
        sink.process(span);
        span = buf.span(static_cast<int>(y), 0, 0);
        count = 0;
      };
      for (int i = 0; i < width; ++i) {
        const double x = xll + i;
        // A span holds consecutive pixels: a clear bit or the window's edge ends it.
        if (x < 0 || x >= fb_.width() || !bitmap_bit(bitmap, width, i, j, pixel_store_.unpack)) {
          flush();
          continue;
        }
        if (count == 0) x_first = static_cast<int>(x);
        raster.put(span, count++);
      }
      flush();
    }
  }
  raster_.window.x += xmove;
  raster_.window.y += ymove;
}

namespace {

// The groups [first, end) of a rectangle `count` groups long (A20: group i covers
// [r + z·i, r + z·(i+1)), mirrored for z < 0) that can hold the centre of a pixel of [0, limit):
// those meeting [0, limit], solved for i and widened by one group each way (the placement
// decides exactly). Every group when the zoom or the rounded raster position r is not a finite
// number and the zoom not zero: nothing is clipped then.
std::pair<int, int> visible_groups(double r, double z, int count, int limit) {
  if (!std::isfinite(r) || !std::isfinite(z) || z == 0.0) return {0, count};
  double a = -r / z, b = (limit - r) / z;
  if (a > b) std::swap(a, b);
  const double n = static_cast<double>(count);
  const int first = static_cast<int>(std::clamp(std::floor(a) - 1.0, 0.0, n));
  const int end = static_cast<int>(std::clamp(std::ceil(b) + 1.0, static_cast<double>(first), n));
  return {first, end};
}

}  // namespace

Context::RectanglePlacement Context::place_rectangle(int width, int height, int first_column, int first_row) const {
  // A20: the raster position is rounded (⌊x + ½⌋), then group (i, j) covers
  // [x + zx·i, x + zx·(i+1)) × [y + zy·j, y + zy·(j+1)); a fragment is produced for each pixel
  // whose centre lies inside or on the bottom/left boundary.
  const RasterVertex& rp = raster_.window;
  const double xr = round_half_up(rp.x), yr = round_half_up(rp.y);
  const double zx = zoom_x_, zy = zoom_y_;
  auto pixel_range = [](double a, double b, int limit, int& lo, int& hi) {
    const double mn = std::min(a, b), mx = std::max(a, b);
    // Clamped in double first: a far raster position or a huge zoom must not overflow int
    // (found by fuzzing); a NaN bound gives an empty range.
    const double first = std::ceil(mn - 0.5), last = std::ceil(mx - 0.5) - 1.0;
    if (!(first <= last)) {
      lo = 0, hi = -1;
      return;
    }
    lo = static_cast<int>(std::clamp(first, 0.0, static_cast<double>(limit)));
    hi = static_cast<int>(std::clamp(last, -1.0, static_cast<double>(limit - 1)));
  };
  RectanglePlacement placement;
  const int xr_int = static_cast<int>(std::clamp(xr, -1.0e9, 1.0e9));
  for (int step = 0; step < width; ++step) {
    const int i = zx >= 0 ? step : width - 1 - step;
    const double g = static_cast<double>(first_column) + i;  // the group's index in the whole rectangle
    int lo, hi;
    if (zx == 1.0) {
      // Zoom 1: group i covers [xr + i, xr + i + 1), whose only centre is pixel xr + i.
      const std::int64_t x = std::int64_t{xr_int} + first_column + i;
      if (x < 0 || x >= fb_.width()) continue;
      lo = hi = static_cast<int>(x);
    } else {
      pixel_range(xr + zx * g, xr + zx * (g + 1.0), fb_.width(), lo, hi);
    }
    for (int x = lo; x <= hi; ++x) {
      if (placement.source_column.empty()) placement.x_first = x;
      placement.source_column.push_back(i);
    }
  }
  const std::vector<int>& columns = placement.source_column;
  placement.identity = static_cast<int>(columns.size()) == width;
  for (std::size_t c = 0; placement.identity && c < columns.size(); ++c)
    placement.identity = columns[c] == static_cast<int>(c);
  placement.rows.resize(static_cast<std::size_t>(height));
  for (int j = 0; j < height; ++j) {
    std::array<int, 2>& r = placement.rows[static_cast<std::size_t>(j)];
    const double g = static_cast<double>(first_row) + j;
    pixel_range(yr + zy * g, yr + zy * (g + 1.0), fb_.height(), r[0], r[1]);
  }
  return placement;
}

void Context::draw_pixel_rectangle(int width, int height, const std::vector<Rgba>* rgba,
                                   const std::vector<double>* depth, int first_column, int first_row) {
  counters().pixels_drawn += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  draw_pixel_rows(prepare_rectangle_fragments(), place_rectangle(width, height, first_column, first_row), width, 0,
                  height,
                  rgba ? rgba->data() : nullptr, depth ? depth->data() : nullptr);
}

Context::RasterFragments Context::prepare_rectangle_fragments() {
  TriangleOptions options;
  prepare_fragment_stages(options);
  return raster_fragments(options);
}

void Context::draw_pixel_rows(const RasterFragments& raster, const RectanglePlacement& placement, int width,
                              int first_row, int rows, const Rgba* rgba, const double* depth,
                              const std::uint16_t* codes) {
  draw_pixel_rows(raster, placement, width, first_row, rows, rgba, depth, codes, fragment_sink(), counters(),
                  scratch_->spans);
}

void Context::draw_pixel_rows(const RasterFragments& raster, const RectanglePlacement& placement, int width,
                              int first_row, int rows, const Rgba* rgba, const double* depth,
                              const std::uint16_t* codes, FragmentSink& sink, Counters& c, SpanBuffers& buf) const {
  const std::vector<int>& source_column = placement.source_column;
  const int count = static_cast<int>(source_column.size());
  if (count == 0) return;
  const bool colour = rgba || codes;
  // Final conversion (§3.6.4): clamp to [0, 1], then to fixed point — once per source row.
  double color_max[4];
  for (int k = 0; k < 4; ++k) color_max[k] = static_cast<double>(max_code(fragment_bits_[k]));
  std::vector<std::uint16_t> converted(rgba ? 4 * static_cast<std::size_t>(width) : 0);
  std::vector<std::uint32_t> row_depth(colour ? 0 : static_cast<std::size_t>(width));
  for (int j = first_row; j < first_row + rows; ++j) {
    const auto [row_lo, row_hi] = placement.rows[static_cast<std::size_t>(j)];
    if (row_lo > row_hi) continue;
    const std::size_t row = static_cast<std::size_t>(j - first_row) * static_cast<std::size_t>(width);
    const std::uint16_t* row_codes = codes ? codes + 4 * row : converted.data();
    if (rgba) {
      color_codes_from_reals(rgba + row, static_cast<std::size_t>(width), color_max, converted.data());
    } else if (!codes) {
      for (int i = 0; i < width; ++i)
        row_depth[static_cast<std::size_t>(i)] =
            fb_.config.depth_bits ? float_to_fixed(depth[row + static_cast<std::size_t>(i)], fb_.config.depth_bits) : 0;
    }
    for (int y = row_lo; y <= row_hi; ++y) {
      // The stages after this may change the span's colours: each window row starts afresh.
      FragmentSpan span = buf.span(y, placement.x_first, count);
      raster.put(span, 0, count, !colour, colour);
      if (colour && placement.identity) {
        std::copy_n(row_codes, 4 * count, span.rgba);
      } else if (colour) {
        for (int k = 0; k < count; ++k)
          std::copy_n(row_codes + 4 * static_cast<std::size_t>(source_column[static_cast<std::size_t>(k)]), 4,
                      span.rgba + 4 * k);
      } else {
        for (int k = 0; k < count; ++k)
          span.depth[k] = row_depth[static_cast<std::size_t>(source_column[static_cast<std::size_t>(k)])];
      }
      c.fragments_generated += static_cast<std::uint64_t>(count);
      sink.process(span);
    }
  }
}

void Context::copy_bands_on_lanes(const SourceCodes& source, const RectanglePlacement& placement, int width,
                                  int height, int band_rows) {
  // The bands are independent: each reads its own rows of the copied source and writes the
  // window rows its source rows are placed on (distinct source rows never share a window
  // row), through stages connected to the same setup; with no histogram or minmax to
  // collect, the transfer reads its state only. The counters are sums.
  TriangleOptions options;
  const FragmentStagesSetup setup = fragment_stages_setup(options);
  primitive_setup_valid_ = false;  // as prepare_fragment_stages would leave it
  if (setup.texture) TextureStage::make_caches(setup.texture_setup, rows_on_lanes());
  const RasterFragments raster = raster_fragments(options);
  transfer_bands_on_lanes(source, width, height, 2, band_rows, &setup,
                          [&](LaneStages& lane, const Rgba* band, int first_row, int rows) {
                            draw_pixel_rows(raster, placement, width, first_row, rows, band, nullptr, nullptr,
                                            *lane.stages.first, lane.counters, lane.spans);
                          });
}

bool Context::copy_source_needed(const RectanglePlacement& placement, int y, int height) const {
  const ColorPlane* read = color_buffer(pixel_.read_buffer);
  if (std::none_of(draw_buffer_ids_.begin(), draw_buffer_ids_.end(),
                   [&](ColorBufferId id) { return &fb_.color[static_cast<int>(id)] == read; }))
    return false;
  for (int j = 0; j < height; ++j) {
    const auto [row_lo, row_hi] = placement.rows[static_cast<std::size_t>(j)];
    // The source rows among the window rows source row j is drawn on: at most its own.
    const std::int64_t a = std::max<std::int64_t>(row_lo, y), b = std::min<std::int64_t>(row_hi, std::int64_t{y} + height - 1);
    if (a <= b && (a != b || a != std::int64_t{y} + j)) return true;
  }
  return false;
}

void Context::copy_pixels_through_table(const SourceCodes& source, const RectanglePlacement& placement, int width,
                                        int height, const std::vector<Rgba>& table_reals) {
  // The fragment codes of every code (draw_pixel_rows's final conversion of its transferred
  // reals), looked up per pixel: the same codes as converting each pixel.
  double color_max[4];
  for (int k = 0; k < 4; ++k) color_max[k] = static_cast<double>(max_code(fragment_bits_[k]));
  std::vector<std::uint16_t> table(4 * table_reals.size());
  color_codes_from_reals(table_reals.data(), table_reals.size(), color_max, table.data());
  const std::uint64_t n = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  count_transfer(transfer_, transform_.color.back(), n, n, counters());
  constexpr int kBandRows = 16;
  const std::size_t row_codes = 4 * static_cast<std::size_t>(width);
  if (scratch_->lanes && height > kBandRows) {
    TriangleOptions options;
    const FragmentStagesSetup setup = fragment_stages_setup(options);
    primitive_setup_valid_ = false;  // as prepare_fragment_stages would leave it
    if (setup.texture) TextureStage::make_caches(setup.texture_setup, rows_on_lanes());
    const RasterFragments raster = raster_fragments(options);
    bands_on_pixel_lanes(height, kBandRows, &setup, [&](int index, int first, int end) {
      Scratch::PixelLane& lane = *scratch_->pixel_lanes[static_cast<std::size_t>(index)];
      lane.band_codes.resize(row_codes * static_cast<std::size_t>(end - first));
      source.through_table(first, end - first, table.data(), lane.band_codes.data(), row_codes);
      draw_pixel_rows(raster, placement, width, first, end - first, nullptr, nullptr, lane.band_codes.data(),
                      *lane.stages.first, lane.counters, lane.spans);
    });
    return;
  }
  const RasterFragments raster = prepare_rectangle_fragments();
  std::vector<std::uint16_t> band(row_codes * static_cast<std::size_t>(std::min(height, kBandRows)));
  for (int j = 0; j < height; j += kBandRows) {
    const int rows = std::min(kBandRows, height - j);
    source.through_table(j, rows, table.data(), band.data(), row_codes);
    draw_pixel_rows(raster, placement, width, j, rows, nullptr, nullptr, band.data());
  }
}

void Context::bands_on_lanes(int rows, int band_rows, const std::function<void(int, int, int)>& body) {
  const int bands = (rows + band_rows - 1) / band_rows;
  std::atomic<int> next_band{0};
  scratch_->lanes->run_task([&](int lane) {
    for (int band = next_band++; band < bands; band = next_band++)
      body(lane, band * band_rows, std::min(rows, (band + 1) * band_rows));
  });
}

const RowSplitter* Context::rows_on_lanes() {
  if (!scratch_->lanes) return nullptr;
  if (!scratch_->rows_on_lanes)
    scratch_->rows_on_lanes = [this](int rows, const std::function<void(int, int)>& body) {
      constexpr int kBandRows = 16;
      if (rows <= kBandRows || !scratch_->lanes) return body(0, rows);
      bands_on_lanes(rows, kBandRows, [&](int, int first, int end) { body(first, end); });
    };
  return &scratch_->rows_on_lanes;
}

void Context::bands_on_pixel_lanes(int height, int band_rows, const FragmentStagesSetup* setup,
                                   const std::function<void(int lane, int first, int end)>& body) {
  std::vector<std::unique_ptr<Scratch::PixelLane>>& pixel_lanes = scratch_->pixel_lanes;
  while (pixel_lanes.size() < static_cast<std::size_t>(scratch_->lanes->lanes()))
    pixel_lanes.push_back(std::make_unique<Scratch::PixelLane>(fb_, fb_.config.width));
  for (auto& lane : pixel_lanes) {
    lane->counters = Counters{};
    if (setup) lane->stages.connect(*setup);
  }
  bands_on_lanes(height, band_rows, body);
  Counters& c = counters();
  for (const auto& lane : pixel_lanes) c += lane->counters;
}

void Context::transfer_bands_on_lanes(const SourceCodes& source, int width, int height, int dims, int band_rows,
                                      const FragmentStagesSetup* setup, const TransferredBandUse& use) {
  const Mat4& matrix = transform_.color.back();
  bands_on_pixel_lanes(height, band_rows, setup, [&](int index, int first, int end) {
    Scratch::PixelLane& lane = *scratch_->pixel_lanes[static_cast<std::size_t>(index)];
    int rows = end - first, w = width;
    lane.band.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(rows));
    source.to_reals(first, rows, lane.band.data());
    transfer_rgba(lane.band, w, rows, transfer_, matrix, lane.counters, dims);
    use(lane, lane.band.data(), first, rows);
  });
}

void Context::draw_stencil_rectangle(int width, int height, const std::vector<double>& indices, int first_column,
                                     int first_row) {
  Counters& c = counters();
  c.pixels_drawn += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  const RectanglePlacement placement = place_rectangle(width, height, first_column, first_row);
  const int bits = fb_.config.stencil_bits;
  const auto mask = static_cast<std::uint8_t>(fb_control_.stencil_writemask & max_code(bits));
  // §4.3.1: pixel ownership (the window) and the scissor test only; no fragment is produced.
  const auto [x_lo, y_lo, x_hi, y_hi] = scissored_window(fragment_, fb_.width(), fb_.height());
  std::uint64_t written = 0;
  for (int j = 0; j < height; ++j) {
    const auto [row_lo, row_hi] = placement.rows[static_cast<std::size_t>(j)];
    for (int y = std::max(row_lo, y_lo); y <= row_hi && y < y_hi; ++y)
      for (std::size_t k = 0; k < placement.source_column.size(); ++k) {
        const int x = placement.x_first + static_cast<int>(k);
        if (x < x_lo || x >= x_hi) continue;
        const double index = indices[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) +
                                     static_cast<std::size_t>(placement.source_column[k])];
        std::uint8_t& s = fb_.stencil[fb_.pixel_index(x, y)];
        s = static_cast<std::uint8_t>((s & ~mask) | (index_low_bits(index, bits) & mask));
        ++written;
      }
  }
  c.stencil_bits_written += written * static_cast<std::uint64_t>(bits);
}

void Context::read_framebuffer_stencil(int x, int y, int width, int height, std::vector<double>& out) const {
  // Pixels outside the window are undefined: they read as 0 here, as colour and depth do.
  out.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0);
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const std::int64_t px = std::int64_t{x} + i, py = std::int64_t{y} + j;
      if (px < 0 || py < 0 || px >= fb_.width() || py >= fb_.height()) continue;
      out[static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i)] =
          fb_.stencil[fb_.pixel_index(static_cast<int>(px), static_cast<int>(py))];
    }
}


void Context::glDrawPixels(GLsizei width, GLsizei height, GLenum format, GLenum type, const void* pixels) {
  PASSIM_ENTRY(width, height, format, type,
               pixels)
  if (width < 0 || height < 0) return set_error(GL_INVALID_VALUE);
  if (!is_pixel_type(type)) return set_error(GL_INVALID_ENUM);
  if (format == GL_STENCIL_INDEX && fb_.config.stencil_bits == 0) return set_error(GL_INVALID_OPERATION);
  if (format == GL_COLOR_INDEX) {
    warn_once("glDrawPixels with GL_COLOR_INDEX is not modelled yet: ignored");
    return;
  }
  if (format != GL_STENCIL_INDEX && format != GL_DEPTH_COMPONENT && !is_color_pixel_format(format))
    return set_error(GL_INVALID_ENUM);
  if (format == GL_DEPTH_COMPONENT && fb_.config.depth_bits == 0) return set_error(GL_INVALID_OPERATION);
  if (!raster_.valid || width == 0 || height == 0 || !pixels) return;  // §3.6.4: invalid raster position: nothing
  // Work proportional to what is drawn (issue 21), as glCopyPixels: only the groups that can
  // land in the window are unpacked, transferred and placed — where the whole image would place
  // them. The sub-image is the same memory entered further on (§3.6.4): SKIP_PIXELS and SKIP_ROWS
  // grow by the groups and rows left out, the row length stays the image's. Not with a
  // convolution, histogram or minmax, which see the whole image.
  int first_column = 0, first_row = 0, w = width, h = height;
  PixelStore store = pixel_store_.unpack;
  if (!is_color_pixel_format(format) ||
      (!active_convolution(transfer_, 2) && !transfer_.histogram.enabled && !transfer_.minmax.enabled)) {
    const auto [c0, c1] = visible_groups(round_half_up(raster_.window.x), zoom_x_, width, fb_.width());
    const auto [r0, r1] = visible_groups(round_half_up(raster_.window.y), zoom_y_, height, fb_.height());
    if (c1 <= c0 || r1 <= r0) return;
    constexpr std::int64_t kIntMax = std::numeric_limits<int>::max();
    if (std::int64_t{store.skip_pixels} + c0 <= kIntMax && std::int64_t{store.skip_rows} + r0 <= kIntMax) {
      if (store.row_length == 0) store.row_length = width;
      store.skip_pixels += c0, store.skip_rows += r0;
      first_column = c0, first_row = r0, w = c1 - c0, h = r1 - r0;
    }
  }
  if (!rectangle_fits_in_memory(w, h)) return;
  if (format == GL_STENCIL_INDEX) {
    std::vector<double> indices;
    unpack_indices(pixels, w, h, format, type, store, indices);
    transfer_stencil(indices, transfer_, counters());
    draw_stencil_rectangle(w, h, indices, first_column, first_row);
  } else if (format == GL_DEPTH_COMPONENT) {
    std::vector<double> depth;
    unpack_depth(pixels, w, h, type, store, depth);
    transfer_depth(depth, transfer_);
    draw_pixel_rectangle(w, h, nullptr, &depth, first_column, first_row);
  } else {
    std::vector<Rgba> rgba;
    unpack_rgba(pixels, w, h, format, type, store, rgba);
    // A REDUCE convolution shrinks the image (never clipped: first_column = first_row = 0).
    if (transfer_rgba(rgba, w, h, transfer_, transform_.color.back(), counters()) && w > 0 && h > 0)
      draw_pixel_rectangle(w, h, &rgba, nullptr, first_column, first_row);
  }
}

void Context::glReadPixels(GLint x, GLint y, GLsizei width, GLsizei height, GLenum format, GLenum type,
                           void* pixels) {
  PASSIM_ENTRY(x, y, width, height, format, type, pixels)
  if (width < 0 || height < 0) return set_error(GL_INVALID_VALUE);
  if (!is_pixel_type(type)) return set_error(GL_INVALID_ENUM);
  if (format == GL_COLOR_INDEX) return set_error(GL_INVALID_OPERATION);  // RGBA mode
  if (format == GL_STENCIL_INDEX) {
    if (fb_.config.stencil_bits == 0) return set_error(GL_INVALID_OPERATION);
    if (width == 0 || height == 0 || !rectangle_fits_in_memory(width, height)) return;
    Counters& c = counters();
    c.pixels_read += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    std::vector<double> indices;
    read_framebuffer_stencil(x, y, width, height, indices);
    c.stencil_bits_read += indices.size() * static_cast<std::uint64_t>(fb_.config.stencil_bits);
    transfer_stencil(indices, transfer_, c);
    pack_indices(indices, width, height, type, pixel_store_.pack, pixels);
    return;
  }
  if (format != GL_DEPTH_COMPONENT && !is_color_pixel_format(format)) return set_error(GL_INVALID_ENUM);
  if (format == GL_DEPTH_COMPONENT && fb_.config.depth_bits == 0) return set_error(GL_INVALID_OPERATION);
  if (width == 0 || height == 0 || !rectangle_fits_in_memory(width, height)) return;
  Counters& c = counters();
  c.pixels_read += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  std::vector<Rgba> out;
  if (format == GL_DEPTH_COMPONENT) {
    std::vector<double> depth;
    read_framebuffer_depth(x, y, width, height, depth);
    transfer_depth(depth, transfer_);
    out.resize(depth.size());
    for (std::size_t p = 0; p < depth.size(); ++p) out[p] = {depth[p], 0, 0, 1};
  } else {
    read_framebuffer_rgba(x, y, width, height, out);
    // A sink consumes the pixels: nothing is returned. §4.3.2: REDUCE shrinks the image returned.
    if (!transfer_rgba(out, width, height, transfer_, transform_.color.back(), c)) return;
    if (width <= 0 || height <= 0) return;
    // §4.3.2: luminance is R + G + B (unweighted), clamped by the packing.
    if (format == GL_LUMINANCE || format == GL_LUMINANCE_ALPHA)
      for (Rgba& p : out) p[0] = p[0] + p[1] + p[2];
  }
  pack_rgba(out, width, height, format, type, pixel_store_.pack, pixels);
}

void Context::glCopyPixels(GLint x_requested, GLint y_requested, GLsizei width_requested, GLsizei height_requested,
                           GLenum type) {
  PASSIM_ENTRY(x_requested, y_requested, width_requested, height_requested, type)
  if (type != GL_COLOR && type != GL_DEPTH && type != GL_STENCIL) return set_error(GL_INVALID_ENUM);
  if (width_requested < 0 || height_requested < 0) return set_error(GL_INVALID_VALUE);
  if ((type == GL_DEPTH && fb_.config.depth_bits == 0) || (type == GL_STENCIL && fb_.config.stencil_bits == 0))
    return set_error(GL_INVALID_OPERATION);
  if (!raster_.valid || width_requested == 0 || height_requested == 0) return;
  // Work proportional to what is drawn (issue 21): a source pixel whose group (A20) lands
  // outside the window makes no fragment, and each pixel's transfer is its own, so only the
  // columns and rows that can reach the window are read, transferred and placed — placed where
  // the whole rectangle would put them. Not so when a convolution (its neighbours) or a
  // histogram or minmax (every pixel counts, §3.6.3) sees the whole rectangle.
  int first_column = 0, first_row = 0, width = width_requested, height = height_requested;
  if (type != GL_COLOR || (!active_convolution(transfer_, 2) && !transfer_.histogram.enabled && !transfer_.minmax.enabled)) {
    const auto [c0, c1] = visible_groups(round_half_up(raster_.window.x), zoom_x_, width, fb_.width());
    const auto [r0, r1] = visible_groups(round_half_up(raster_.window.y), zoom_y_, height, fb_.height());
    if (c1 <= c0 || r1 <= r0) return;
    first_column = c0, first_row = r0, width = c1 - c0, height = r1 - r0;
  }
  // The source moves with the clipping; beyond the largest int it lies outside the window,
  // where every pixel reads as undefined (0) wherever it starts.
  const auto clamp_int = [](std::int64_t v) {
    return static_cast<int>(std::min<std::int64_t>(v, std::numeric_limits<int>::max()));
  };
  const int x = clamp_int(std::int64_t{x_requested} + first_column), y = clamp_int(std::int64_t{y_requested} + first_row);
  if (!rectangle_fits_in_memory(width, height)) return;
  Counters& c = counters();
  c.pixels_read += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
  // A22: the whole source is read (through the transfer operations, once) before drawing.
  if (type == GL_STENCIL) {
    std::vector<double> indices;
    read_framebuffer_stencil(x, y, width, height, indices);
    c.stencil_bits_read += indices.size() * static_cast<std::uint64_t>(fb_.config.stencil_bits);
    transfer_stencil(indices, transfer_, c);
    draw_stencil_rectangle(width, height, indices, first_column, first_row);
  } else if (type == GL_DEPTH) {
    std::vector<double> depth;
    read_framebuffer_depth(x, y, width, height, depth);
    c.depth_bits_read += depth.size() * static_cast<std::uint64_t>(fb_.config.depth_bits);
    transfer_depth(depth, transfer_);
    draw_pixel_rectangle(width, height, nullptr, &depth, first_column, first_row);
  } else {
    const auto& b = fb_.config.color_bits;
    c.color_bits_read += static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) *
                         static_cast<std::uint64_t>(b[0] + b[1] + b[2] + b[3]);
    if (active_convolution(transfer_, 2)) {
      // A convolution needs its neighbours: the whole rectangle as reals, in buffers kept
      // between calls (a fresh 32-byte-a-pixel buffer per call costs more than the filter);
      // converted whole before anything is drawn, so read in place.
      const SourceCodes source = read_framebuffer_codes(x, y, width, height, nullptr);
      std::vector<Rgba>& rgba = scratch_->rectangle;
      rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
      source.to_reals(0, height, rgba.data());
      int w = width, h = height;
      if (transfer_rgba(rgba, w, h, transfer_, transform_.color.back(), c, 2, &scratch_->rectangle_spare,
                        rows_on_lanes()) &&
          w > 0 && h > 0)
        draw_pixel_rectangle(w, h, &rgba, nullptr);
      return;
    }
    // Every other step is per pixel: convert, transfer and draw a band of rows at a time
    // (the same operations in the same order as the whole rectangle at once; A22 holds, as
    // the source was read whole above).
    const std::uint64_t n = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
    c.pixels_drawn += n;
    const RectanglePlacement placement = place_rectangle(width, height, first_column, first_row);
    std::vector<std::uint16_t> copy;
    const SourceCodes source =
        read_framebuffer_codes(x, y, width, height, copy_source_needed(placement, y, height) ? &copy : nullptr);
    const std::vector<Rgba> table_reals = transfer_table(source, 2, n);
    if (!table_reals.empty()) return copy_pixels_through_table(source, placement, width, height, table_reals);
    constexpr int kBandRows = 16;
    if (scratch_->lanes && !transfer_.histogram.enabled && !transfer_.minmax.enabled && height > kBandRows) {
      copy_bands_on_lanes(source, placement, width, height, kBandRows);
      return;
    }
    const RasterFragments raster = prepare_rectangle_fragments();
    std::vector<Rgba> band(static_cast<std::size_t>(width) * static_cast<std::size_t>(std::min(height, kBandRows)));
    for (int j = 0; j < height; j += kBandRows) {
      int rows = std::min(kBandRows, height - j), w = width;
      band.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(rows));
      source.to_reals(j, rows, band.data());
      // A histogram or minmax sink counts every band and draws none.
      if (transfer_rgba(band, w, rows, transfer_, transform_.color.back(), c))
        draw_pixel_rows(raster, placement, width, j, rows, band.data(), nullptr);
    }
  }
}

}  // namespace passim
