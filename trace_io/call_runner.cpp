#include "trace_io/call_runner.hpp"

#include <fmt/format.h>

#include <map>

#include "pipeline/gl.hpp"
#include "client/pixel_unpack.hpp"

namespace passim {

namespace {
[[noreturn]] void reject(const std::string& message) { throw CallRejected(message); }
}  // namespace

// Pointer arguments whose length another argument gives.
void CallRunner::check_counts(const CallInfo& info, const std::vector<Value>& values) const {
  const std::string_view fn = info.name;
  auto need = [&](std::size_t count_arg, std::size_t data_arg, const char* what, const char* noun) {
    if (values[count_arg].i > 0 && values[data_arg].count < static_cast<std::size_t>(values[count_arg].i))
      reject(fmt::format("{}: {} is {} but {} {} are given", fn, what, values[count_arg].i, values[data_arg].count, noun));
  };
  if (fn == "glDrawElements") need(1, 3, "count", "indices");
  if (fn == "glPixelMapfv" || fn == "glPixelMapusv" || fn == "glPixelMapuiv") need(1, 2, "mapsize", "values");
  if (fn == "glCallLists") need(0, 2, "n", "names");
  if ((fn == "glGenTextures" || fn == "glDeleteTextures") && values[0].i > 65536)
    reject(fmt::format("{}: n = {} is above the 65536 names a trace may ask for at once", fn, values[0].i));
  if (fn == "glDeleteTextures") need(0, 1, "n", "names");
}

// Image data must hold every byte the call will read under the current unpack modes.
void CallRunner::check_image_data(const std::string& fn, const std::vector<Value>& v) const {
  int w = 0, h = 1;
  std::size_t format = 0, type = 0, data = 0;
  if (fn == "glTexImage1D") { w = static_cast<int>(v[3].i); format = 5; type = 6; data = 7; }
  else if (fn == "glTexImage2D") { w = static_cast<int>(v[3].i); h = static_cast<int>(v[4].i); format = 6; type = 7; data = 8; }
  else if (fn == "glTexSubImage1D") { w = static_cast<int>(v[3].i); format = 4; type = 5; data = 6; }
  else if (fn == "glTexSubImage2D") { w = static_cast<int>(v[4].i); h = static_cast<int>(v[5].i); format = 6; type = 7; data = 8; }
  else if (fn == "glColorTable") { w = static_cast<int>(v[2].i); format = 3; type = 4; data = 5; }
  else if (fn == "glColorSubTable") { w = static_cast<int>(v[2].i); format = 3; type = 4; data = 5; }
  else if (fn == "glConvolutionFilter1D") { w = static_cast<int>(v[2].i); format = 3; type = 4; data = 5; }
  else if (fn == "glConvolutionFilter2D") { w = static_cast<int>(v[2].i); h = static_cast<int>(v[3].i); format = 4; type = 5; data = 6; }
  else if (fn == "glSeparableFilter2D") {
    const GLenum f = static_cast<GLenum>(v[4].i), t = static_cast<GLenum>(v[5].i);
    if (format_components(f) == 0 || !is_pixel_type(t)) return;
    for (const auto& [arg, n] : {std::pair{6, v[2].i}, std::pair{7, v[3].i}}) {
      if (!v[static_cast<std::size_t>(arg)].bytes || n <= 0) continue;
      const std::size_t need = image_bytes(static_cast<int>(n), 1, f, t, ctx_.unpack_store());
      if (v[static_cast<std::size_t>(arg)].bytes->size() < need)
        reject(fmt::format("glSeparableFilter2D: argument {} needs {} bytes, the trace gives {}", arg + 1, need,
                           v[static_cast<std::size_t>(arg)].bytes->size()));
    }
    return;
  }
  else if (fn == "glDrawPixels") { w = static_cast<int>(v[0].i); h = static_cast<int>(v[1].i); format = 2; type = 3; data = 4; }
  else if (fn == "glBitmap") {
    if (!v[6].bytes || v[6].count == 0) return;
    const std::size_t need = bitmap_bytes(static_cast<int>(v[0].i), static_cast<int>(v[1].i), ctx_.unpack_store());
    if (v[6].bytes->size() < need)
      reject(fmt::format("glBitmap: the bitmap needs {} bytes under the current unpack modes, the trace gives {}", need,
                         v[6].bytes->size()));
    return;
  }
  else return;
  const GLenum f = static_cast<GLenum>(v[format].i), t = static_cast<GLenum>(v[type].i);
  if (!v[data].bytes || v[data].count == 0 || w <= 0 || h <= 0 || format_components(f) == 0 || !is_pixel_type(t))
    return;  // no data, or a call the GL rejects before reading
  const std::size_t need = image_bytes(w, h, f, t, ctx_.unpack_store());
  if (v[data].bytes->size() < need)
    reject(fmt::format("{}: the image needs {} bytes under the current unpack modes, the trace gives {}", fn, need,
                       v[data].bytes->size()));
}

void CallRunner::run(const CallInfo& info, const std::vector<Value>& values, const std::string& where) {
  check_counts(info, values);
  ctx_.set_source_location(where);
  if (info.query) return;  // queries change nothing; their output arguments cannot be replayed
  check_image_data(std::string(info.name), values);
  try {
    info.invoke(ctx_, values);
  } catch (const ClientDataError& e) {
    reject(e.what());
  }
  if (info.recorded_at_draw) {
    static const std::map<std::string_view, GLenum> arrays = {{"glVertexPointer", GL_VERTEX_ARRAY},
                                                               {"glNormalPointer", GL_NORMAL_ARRAY},
                                                               {"glColorPointer", GL_COLOR_ARRAY},
                                                               {"glTexCoordPointer", GL_TEXTURE_COORD_ARRAY}};
    const Value& data = values.back();
    ctx_.set_client_array_extent(arrays.at(info.name), data.bytes ? data.bytes->size() : 0);
    keep_alive_.push_back(data.bytes);
  }
  report_errors();
}

void CallRunner::report_errors() {
  const auto& log = ctx_.error_log();
  for (; reported_errors_ < log.size(); ++reported_errors_) {
    const GlErrorRecord& e = log[reported_errors_];
    std::string msg = fmt::format("{} raised by {}", enum_name(e.error), e.call);
    if (diagnostics_) *diagnostics_ << fmt::format("{}: {}\n", e.where, msg);
    if (strict_) reject(msg + " (--strict)");
  }
}

}  // namespace passim
