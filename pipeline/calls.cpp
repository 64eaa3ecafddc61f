// The call table (see calls.hpp). One row per GL entry point.
#include "pipeline/calls.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "client/pixel_unpack.hpp"
#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"

namespace passim {
namespace {

// The results of the call running under run_collecting (this thread's): where its output
// arguments point and its return value goes.
thread_local CallResults* collecting = nullptr;

// The GL type of an output element the entry point writes (void: the row's `type` argument).
template <class T>
constexpr GLenum output_type() {
  if constexpr (std::is_same_v<T, GLfloat>) return GL_FLOAT;
  else if constexpr (std::is_same_v<T, GLdouble>) return GL_DOUBLE;
  else if constexpr (std::is_same_v<T, GLint>) return GL_INT;
  else if constexpr (std::is_same_v<T, GLuint>) return GL_UNSIGNED_INT;
  else if constexpr (std::is_same_v<T, GLboolean>) return GL_UNSIGNED_BYTE;
  else return 0;
}

template <class T>
T arg(const Value& v) {
  if constexpr (std::is_same_v<T, const char*>) {
    return v.str().c_str();
  } else if constexpr (std::is_pointer_v<T> && std::is_const_v<std::remove_pointer_t<T>>) {
    return v.bytes ? reinterpret_cast<T>(v.bytes->data()) : nullptr;
  } else if constexpr (std::is_pointer_v<T>) {
    // An output argument: its room, made by the runner before the call (`i`: which output).
    if (!collecting || v.i < 0 || static_cast<std::size_t>(v.i) >= collecting->outputs.size())
      throw std::logic_error("an output argument without room for it (the call was not run by run_collecting)");
    CallOutput& out = collecting->outputs[static_cast<std::size_t>(v.i)];
    if constexpr (output_type<std::remove_pointer_t<T>>() != 0) out.type = output_type<std::remove_pointer_t<T>>();
    return reinterpret_cast<T>(out.bytes.data());
  } else if constexpr (std::is_floating_point_v<T>) {
    return static_cast<T>(v.d);
  } else {
    return static_cast<T>(v.i);
  }
}

template <auto MF>
struct Invoker;
template <class R, class... A, R (Context::*MF)(A...)>
struct Invoker<MF> {
  static void call(Context& c, std::span<const Value> v) { call_with(c, v, std::index_sequence_for<A...>{}); }
  template <std::size_t... I>
  static void call_with(Context& c, [[maybe_unused]] std::span<const Value> v, std::index_sequence<I...>) {
    if constexpr (std::is_void_v<R>) {
      (c.*MF)(arg<A>(v[I])...);
    } else {
      const R r = (c.*MF)(arg<A>(v[I])...);
      if (!collecting) return;
      collecting->returned = true;
      if constexpr (std::is_pointer_v<R>) collecting->value.set_str(r ? reinterpret_cast<const char*>(r) : "");
      else collecting->value.i = static_cast<std::int64_t>(r);
    }
  }
  static constexpr std::size_t arity = sizeof...(A);
  static constexpr bool returns = !std::is_void_v<R>;
};

enum Flags : unsigned {
  kNone = 0,
  kNotCompiled = 1,  // §5.4: executed immediately, never put in a list
  kInBeginEnd = 2,   // §2.6.3: allowed between Begin and End
  kQuery = 4,        // output arguments
  kQueues = 8,       // queues primitives and changes no state the fragment stages read
  kDraws = 16,       // draws: primitives, pixels, clears, accumulation
  kReadsArrays = 32,  // reads the enabled client arrays (§2.8): recorded and compiled with their data
};

[[noreturn]] void bad_row(std::string_view name, const std::string& why) {
  std::fprintf(stderr, "passim: internal error: call-table row %.*s: %s\n", static_cast<int>(name.size()),
               name.data(), why.c_str());
  std::abort();
}

// Parses "kind[rule]:name" tokens (see calls.hpp); names in rules resolve to argument indices.
std::vector<CallInfo::Param> parse_signature(std::string_view call, std::string_view sig) {
  std::vector<CallInfo::Param> params;
  std::vector<std::pair<std::size_t, std::string_view>> rules;  // parameter, rule text
  std::size_t i = 0;
  while (i < sig.size()) {
    std::size_t end = i;
    for (int depth = 0; end < sig.size() && (depth > 0 || sig[end] != ' '); ++end)
      depth += sig[end] == '{' ? 1 : sig[end] == '}' ? -1 : 0;
    const std::string_view token = sig.substr(i, end - i);
    i = end + 1;
    const std::size_t colon = token.rfind(':');
    if (colon == std::string_view::npos || colon == 0) bad_row(call, fmt::format("token '{}' has no name", token));
    CallInfo::Param p;
    p.kind = token[0];
    p.name = token.substr(colon + 1);
    const std::string_view rule = token.substr(1, colon - 1);
    if (std::strchr("FDIUBGSHVO", p.kind)) {
      if (rule.empty() && p.kind != 'O') bad_row(call, fmt::format("array '{}' has no length rule", p.name));
      p.length = Length::Any;  // refined below, once every name is known
      rules.emplace_back(params.size(), rule);
    } else if (!rule.empty() || !std::strchr("emnzbkiucghwfdsxy", p.kind)) {
      bad_row(call, fmt::format("token '{}' is not a scalar or an array", token));
    }
    params.push_back(p);
  }
  auto index_of = [&](std::string_view name) {
    for (std::size_t k = 0; k < params.size(); ++k)
      if (params[k].name == name) return static_cast<int>(k);
    bad_row(call, fmt::format("a length rule names '{}', which is not a parameter", name));
  };
  for (auto& [k, rule] : rules) {
    CallInfo::Param& p = params[k];
    for (std::size_t j = 0; j < k; ++j)
      if (params[j].name == "type") p.type_arg = static_cast<int>(j);
    if (rule.empty() || rule == "*") {
      p.length = Length::Any;
    } else if (rule == "p") {
      p.length = Length::ByPname;
      p.count_arg = index_of("pname");
    } else if (rule.front() == '[' && rule.back() == ']') {
      p.length = Length::ByArgument;
      p.count_arg = index_of(rule.substr(1, rule.size() - 2));
    } else if (rule.front() == '{' && rule.back() == '}') {
      std::vector<std::string_view> words;
      std::string_view inner = rule.substr(1, rule.size() - 2);
      for (std::size_t a = 0; a < inner.size();) {
        std::size_t b = inner.find(' ', a);
        if (b == std::string_view::npos) b = inner.size();
        if (b > a) words.push_back(inner.substr(a, b - a));
        a = b + 1;
      }
      if (words.size() == 1 && words[0] == "state" && p.kind == 'O') {
        p.length = Length::State;
        continue;
      }
      if (words.size() < 2 || words.size() > 4 || (words[0] != "image" && words[0] != "bitmap"))
        bad_row(call, fmt::format("rule '{}' is not {{image w [h [d]]}} or {{bitmap w h}}", rule));
      p.length = words[0] == "image" ? Length::Image : Length::Bitmap;
      for (std::size_t d = 1; d < words.size(); ++d) p.dims[d - 1] = index_of(words[d]);
      if (p.length == Length::Image) {
        p.format_arg = index_of("format");
        p.type_arg = index_of("type");
      }
    } else {
      int n = 0;
      for (char c : rule) {
        if (c < '0' || c > '9') bad_row(call, fmt::format("length rule '{}' is not known", rule));
        n = n * 10 + (c - '0');
      }
      p.length = Length::Fixed;
      p.fixed_count = n;
    }
    if (p.kind == 'V' && p.type_arg < 0) bad_row(call, "a void* parameter needs a parameter named 'type' before it");
  }
  return params;
}

using StateElements = std::uint64_t (*)(const Context&, std::span<const Value>, std::size_t);

template <auto MF>
CallInfo row(std::string_view name, std::string_view sig, unsigned flags, GLenum client_array = 0,
             StateElements state_elements = nullptr) {
  CallInfo info;
  info.name = name;
  info.signature = sig;
  info.compiled_into_lists = !(flags & (kNotCompiled | kQuery)) && client_array == 0;
  info.allowed_in_begin_end = flags & kInBeginEnd;
  info.keeps_raster_queue = info.allowed_in_begin_end || (flags & kQueues);
  info.draws = flags & kDraws;
  info.reads_client_arrays = flags & kReadsArrays;
  info.query = flags & kQuery;
  info.client_array = client_array;
  info.invoke = &Invoker<MF>::call;
  info.returns_value = Invoker<MF>::returns;
  info.params = parse_signature(name, sig);
  info.state_elements = state_elements;
  for (const CallInfo::Param& p : info.params)
    if ((p.length == Length::State) != (state_elements != nullptr && p.kind == 'O'))
      bad_row(name, "an output sized by {state} needs the row's state_elements, and only such rows have one");
  if (info.params.size() != Invoker<MF>::arity)
    bad_row(name, fmt::format("the signature has {} parameters, the entry point {}", info.params.size(),
                              Invoker<MF>::arity));
  return info;
}

#define ROW(fn, sig, flags) row<&Context::fn>(#fn, sig, flags)
// A query whose output's size is the GL state's ({state}): `sizer` gives it.
#define STATE_QUERY_ROW(fn, sig, sizer) row<&Context::fn>(#fn, sig, kQuery, 0, sizer)

// The {state} outputs' sizes (by argument position, as the rows below give them).
GLenum enum_at(std::span<const Value> v, std::size_t k) { return static_cast<GLenum>(v[k].i); }
std::uint64_t state_elements(const Context& c, std::span<const Value> v, std::size_t) {
  return c.state_output_elements(enum_at(v, 0));
}
std::uint64_t tex_image_elements(const Context& c, std::span<const Value> v, std::size_t) {
  return c.tex_image_output_elements(enum_at(v, 0), static_cast<GLint>(v[1].i), enum_at(v, 2), enum_at(v, 3));
}
std::uint64_t color_table_elements(const Context& c, std::span<const Value> v, std::size_t) {
  return c.color_table_output_elements(enum_at(v, 0), enum_at(v, 1), enum_at(v, 2));
}
std::uint64_t filter_elements(const Context& c, std::span<const Value> v, std::size_t) {
  return c.filter_output_elements(enum_at(v, 0), enum_at(v, 1), enum_at(v, 2), 0);
}
std::uint64_t separable_elements(const Context& c, std::span<const Value> v, std::size_t param) {
  // row, column; the span argument is unused by GL 1.2 (nothing written).
  return param == 5 ? 0 : c.filter_output_elements(enum_at(v, 0), enum_at(v, 1), enum_at(v, 2), param == 3 ? 1 : 2);
}
std::uint64_t histogram_elements(const Context& c, std::span<const Value> v, std::size_t) {
  return c.histogram_output_elements(enum_at(v, 2), enum_at(v, 3));
}
std::uint64_t minmax_elements(const Context& c, std::span<const Value> v, std::size_t) {
  return c.minmax_output_elements(enum_at(v, 2), enum_at(v, 3));
}
// A client-array pointer call (§2.8): executed at once, recorded with its data at each draw.
#define ARRAY_ROW(fn, sig, array) row<&Context::fn>(#fn, sig, kNotCompiled, array)

// The rows of a family member (context.hpp's type lists give name, n, suffix, C type and the
// scalar and array kinds): the scalar form's signature names its first n parameters from the
// family's names ("h:x h:y"), the vector form reads n values ("S2:v").
#define SIGNATURE_1(k, a, ...) #k ":" #a
#define SIGNATURE_2(k, a, b, ...) SIGNATURE_1(k, a) " " #k ":" #b
#define SIGNATURE_3(k, a, b, c, ...) SIGNATURE_2(k, a, b) " " #k ":" #c
#define SIGNATURE_4(k, a, b, c, d) SIGNATURE_3(k, a, b, c) " " #k ":" #d
#define MEMBER_ROWS(name, n, suffix, kind, Kind, flags, ...)                      \
  ROW(name##n##suffix, SIGNATURE_##n(kind, __VA_ARGS__), flags),                  \
  ROW(name##n##suffix##v, #Kind #n ":v", flags),
#define VERTEX_ROWS(name, n, suffix, T, kind, Kind) MEMBER_ROWS(name, n, suffix, kind, Kind, kInBeginEnd, x, y, z, w)
#define TEX_COORD_ROWS(name, n, suffix, T, kind, Kind) MEMBER_ROWS(name, n, suffix, kind, Kind, kInBeginEnd, s, t, r, q)
#define NORMAL_ROWS(name, n, suffix, T, kind, Kind) MEMBER_ROWS(name, n, suffix, kind, Kind, kInBeginEnd, nx, ny, nz)
#define COLOR_ROWS(name, n, suffix, T, kind, Kind) \
  MEMBER_ROWS(name, n, suffix, kind, Kind, kInBeginEnd, red, green, blue, alpha)
#define RASTER_POS_ROWS(name, n, suffix, T, kind, Kind) MEMBER_ROWS(name, n, suffix, kind, Kind, kNone, x, y, z, w)
// §2.9: the four coordinates, or two corners of two.
#define RECT_ROWS(name, n, suffix, T, kind, Kind)                                      \
  ROW(name##suffix, SIGNATURE_4(kind, x1, y1, x2, y2), kQueues | kDraws),              \
  ROW(name##suffix##v, #Kind "2:v1 " #Kind "2:v2", kQueues | kDraws),

const std::vector<CallInfo>& table() {
  static const std::vector<CallInfo> rows = {
      // errors and state
      ROW(glGetError, "", kNotCompiled),
      ROW(glEnable, "e:cap", kNone),
      ROW(glDisable, "e:cap", kNone),
      ROW(glIsEnabled, "e:cap", kNotCompiled),
      ROW(glGetString, "e:name", kNotCompiled),
      STATE_QUERY_ROW(glGetIntegerv, "e:pname O{state}:params", state_elements),
      STATE_QUERY_ROW(glGetFloatv, "e:pname O{state}:params", state_elements),
      STATE_QUERY_ROW(glGetDoublev, "e:pname O{state}:params", state_elements),
      STATE_QUERY_ROW(glGetBooleanv, "e:pname O{state}:params", state_elements),
      ROW(glHint, "e:target e:mode", kNone),
      ROW(glFlush, "", kNotCompiled),
      ROW(glFinish, "", kNotCompiled),
      // attribute stacks (§6.1.14): the client stack is client state, not compiled (§5.4)
      ROW(glPushAttrib, "b:mask", kNone),
      ROW(glPopAttrib, "", kNone),
      ROW(glPushClientAttrib, "k:mask", kNotCompiled),
      ROW(glPopClientAttrib, "", kNotCompiled),
      // framebuffer control
      ROW(glClear, "b:mask", kDraws),
      ROW(glClearColor, "f:red f:green f:blue f:alpha", kNone),
      ROW(glClearDepth, "d:depth", kNone),
      ROW(glClearStencil, "i:s", kNone),
      ROW(glClearAccum, "f:red f:green f:blue f:alpha", kNone),
      ROW(glAccum, "e:op f:value", kDraws),
      ROW(glColorMask, "z:red z:green z:blue z:alpha", kNone),
      ROW(glDepthMask, "z:flag", kNone),
      ROW(glStencilMask, "u:mask", kNone),
      ROW(glDrawBuffer, "n:mode", kNone),
      ROW(glReadBuffer, "n:mode", kNone),
      // per-fragment operations
      ROW(glScissor, "i:x i:y i:width i:height", kNone),
      ROW(glAlphaFunc, "e:func f:ref", kNone),
      ROW(glStencilFunc, "e:func i:ref u:mask", kNone),
      ROW(glStencilOp, "e:fail e:zfail e:zpass", kNone),
      ROW(glDepthFunc, "e:func", kNone),
      ROW(glBlendFunc, "e:sfactor e:dfactor", kNone),
      ROW(glBlendEquation, "e:mode", kNone),
      ROW(glBlendColor, "f:red f:green f:blue f:alpha", kNone),
      ROW(glLogicOp, "e:opcode", kNone),
      // transformation
      ROW(glViewport, "i:x i:y i:width i:height", kNone),
      ROW(glDepthRange, "d:near_val d:far_val", kNone),
      ROW(glMatrixMode, "e:mode", kNone),
      ROW(glLoadIdentity, "", kNone),
      ROW(glLoadMatrixf, "F16:m", kNone),
      ROW(glLoadMatrixd, "D16:m", kNone),
      ROW(glMultMatrixf, "F16:m", kNone),
      ROW(glMultMatrixd, "D16:m", kNone),
      ROW(glPushMatrix, "", kNone),
      ROW(glPopMatrix, "", kNone),
      ROW(glTranslatef, "f:x f:y f:z", kNone),
      ROW(glTranslated, "d:x d:y d:z", kNone),
      ROW(glRotatef, "f:angle f:x f:y f:z", kNone),
      ROW(glRotated, "d:angle d:x d:y d:z", kNone),
      ROW(glScalef, "f:x f:y f:z", kNone),
      ROW(glScaled, "d:x d:y d:z", kNone),
      ROW(glFrustum, "d:left d:right d:bottom d:top d:near_val d:far_val", kNone),
      ROW(glOrtho, "d:left d:right d:bottom d:top d:near_val d:far_val", kNone),
      ROW(glClipPlane, "e:plane D4:equation", kNone),
      ROW(gluPerspective, "d:fovy d:aspect d:zNear d:zFar", kNone),
      ROW(gluLookAt, "d:eyeX d:eyeY d:eyeZ d:centerX d:centerY d:centerZ d:upX d:upY d:upZ", kNone),
      // vertices (§2.6-2.9): Begin and End, then the families of context.hpp, a row for each
      // member's scalar and vector form from its family's parameter names
      ROW(glBegin, "m:mode", kQueues),
      ROW(glEnd, "", kInBeginEnd | kDraws),
      PASSIM_COORDINATE_TYPES(VERTEX_ROWS, glVertex, 2)
      PASSIM_COORDINATE_TYPES(VERTEX_ROWS, glVertex, 3)
      PASSIM_COORDINATE_TYPES(VERTEX_ROWS, glVertex, 4)
      PASSIM_COORDINATE_TYPES(TEX_COORD_ROWS, glTexCoord, 1)
      PASSIM_COORDINATE_TYPES(TEX_COORD_ROWS, glTexCoord, 2)
      PASSIM_COORDINATE_TYPES(TEX_COORD_ROWS, glTexCoord, 3)
      PASSIM_COORDINATE_TYPES(TEX_COORD_ROWS, glTexCoord, 4)
      PASSIM_NORMAL_TYPES(NORMAL_ROWS, glNormal, 3)
      PASSIM_COLOR_TYPES(COLOR_ROWS, glColor, 3)
      PASSIM_COLOR_TYPES(COLOR_ROWS, glColor, 4)
      ROW(glEdgeFlag, "z:flag", kInBeginEnd),
      ROW(glEdgeFlagv, "B1:flag", kInBeginEnd),
      PASSIM_COORDINATE_TYPES(RECT_ROWS, glRect, 2)
      // vertex arrays
      ROW(glEnableClientState, "e:cap", kNotCompiled),
      ROW(glDisableClientState, "e:cap", kNotCompiled),
      ARRAY_ROW(glVertexPointer, "i:size e:type i:stride V*:pointer", GL_VERTEX_ARRAY),
      ARRAY_ROW(glNormalPointer, "e:type i:stride V*:pointer", GL_NORMAL_ARRAY),
      ARRAY_ROW(glColorPointer, "i:size e:type i:stride V*:pointer", GL_COLOR_ARRAY),
      ARRAY_ROW(glTexCoordPointer, "i:size e:type i:stride V*:pointer", GL_TEXTURE_COORD_ARRAY),
      ARRAY_ROW(glEdgeFlagPointer, "i:stride B*:pointer", GL_EDGE_FLAG_ARRAY),
      // Sets several arrays (Table 2.5); recorded as their pointer calls at each draw, with the
      // enables it changes.
      ARRAY_ROW(glInterleavedArrays, "e:format i:stride B*:pointer", GL_VERTEX_ARRAY),
      ROW(glArrayElement, "i:i", kInBeginEnd | kReadsArrays),
      ROW(glDrawArrays, "m:mode i:first i:count", kQueues | kDraws | kReadsArrays),
      ROW(glDrawElements, "m:mode i:count e:type V[count]:indices", kQueues | kDraws | kReadsArrays),
      ROW(glDrawRangeElements, "m:mode u:start u:end i:count e:type V[count]:indices",
          kQueues | kDraws | kReadsArrays),
      // display lists
      ROW(glNewList, "u:list e:mode", kNotCompiled),
      ROW(glEndList, "", kNotCompiled),
      ROW(glCallList, "u:list", kInBeginEnd | kDraws),
      ROW(glCallLists, "i:n e:type V[n]:lists", kInBeginEnd | kDraws),
      ROW(glGenLists, "i:range", kNotCompiled),
      ROW(glDeleteLists, "u:list i:range", kNotCompiled),
      ROW(glIsList, "u:list", kNotCompiled),
      ROW(glListBase, "u:base", kNone),
      // lighting
      ROW(glShadeModel, "e:mode", kNone),
      ROW(glLightf, "e:light e:pname f:param", kNone),
      ROW(glLighti, "e:light e:pname i:param", kNone),
      ROW(glLightfv, "e:light e:pname Fp:params", kNone),
      ROW(glLightModelf, "e:pname y:param", kNone),
      ROW(glLightModeli, "e:pname x:param", kNone),
      ROW(glLightModelfv, "e:pname Fp:params", kNone),
      ROW(glMaterialf, "e:face e:pname f:param", kInBeginEnd),
      ROW(glMaterialfv, "e:face e:pname Fp:params", kInBeginEnd),
      ROW(glColorMaterial, "e:face e:mode", kNone),
      // rasterization
      ROW(glCullFace, "e:mode", kNone),
      ROW(glFrontFace, "e:mode", kNone),
      ROW(glPolygonMode, "e:face e:mode", kNone),
      ROW(glPolygonOffset, "f:factor f:units", kNone),
      ROW(glPointSize, "f:size", kNone),
      ROW(glLineWidth, "f:width", kNone),
      ROW(glLineStipple, "i:factor w:pattern", kNone),
      // pixel storage and textures
      ROW(glPixelStorei, "e:pname x:param", kNotCompiled),
      ROW(glPixelStoref, "e:pname y:param", kNotCompiled),
      ROW(glGenTextures, "i:n O[n]:textures", kNotCompiled),
      ROW(glDeleteTextures, "i:n U[n]:textures", kNotCompiled),
      ROW(glBindTexture, "e:target u:texture", kNone),
      ROW(glIsTexture, "u:texture", kNotCompiled),
      ROW(glTexImage1D, "e:target i:level x:internalformat i:width i:border e:format e:type V{image width}:pixels", kNone),
      ROW(glTexImage2D, "e:target i:level x:internalformat i:width i:height i:border e:format e:type V{image width height}:pixels", kNone),
      ROW(gluBuild1DMipmaps, "e:target x:internalformat i:width e:format e:type V{image width}:data", kNone),
      ROW(gluBuild2DMipmaps, "e:target x:internalformat i:width i:height e:format e:type V{image width height}:data", kNone),
      ROW(glTexSubImage1D, "e:target i:level i:xoffset i:width e:format e:type V{image width}:pixels", kNone),
      ROW(glTexSubImage2D, "e:target i:level i:xoffset i:yoffset i:width i:height e:format e:type V{image width height}:pixels", kNone),
      ROW(glCopyTexImage1D, "e:target i:level e:internalformat i:x i:y i:width i:border", kNone),
      ROW(glCopyTexImage2D, "e:target i:level e:internalformat i:x i:y i:width i:height i:border", kNone),
      ROW(glCopyTexSubImage1D, "e:target i:level i:xoffset i:x i:y i:width", kNone),
      ROW(glCopyTexSubImage2D, "e:target i:level i:xoffset i:yoffset i:x i:y i:width i:height", kNone),
      STATE_QUERY_ROW(glGetTexImage, "e:target i:level e:format e:type O{state}:pixels", tex_image_elements),
      ROW(glTexParameteri, "e:target e:pname x:param", kNone),
      ROW(glTexParameterf, "e:target e:pname y:param", kNone),
      ROW(glTexParameterfv, "e:target e:pname Fp:params", kNone),
      ROW(glGetTexParameterfv, "e:target e:pname Op:params", kQuery),
      ROW(glGetTexParameteriv, "e:target e:pname Op:params", kQuery),
      ROW(glGetTexLevelParameteriv, "e:target i:level e:pname Op:params", kQuery),
      ROW(glTexEnvi, "e:target e:pname x:param", kNone),
      ROW(glTexEnvf, "e:target e:pname y:param", kNone),
      ROW(glTexEnvfv, "e:target e:pname Fp:params", kNone),
      ROW(glTexGeni, "e:coord e:pname x:param", kNone),
      ROW(glTexGenf, "e:coord e:pname y:param", kNone),
      ROW(glTexGenfv, "e:coord e:pname Fp:params", kNone),
      ROW(glTexGendv, "e:coord e:pname Dp:params", kNone),
      // raster position and pixel rectangles
      PASSIM_COORDINATE_TYPES(RASTER_POS_ROWS, glRasterPos, 2)
      PASSIM_COORDINATE_TYPES(RASTER_POS_ROWS, glRasterPos, 3)
      PASSIM_COORDINATE_TYPES(RASTER_POS_ROWS, glRasterPos, 4)
      ROW(glPixelZoom, "f:xfactor f:yfactor", kNone),
      ROW(glPixelTransferf, "e:pname y:param", kNone),
      ROW(glPixelTransferi, "e:pname x:param", kNone),
      ROW(glPixelMapfv, "e:map i:mapsize F[mapsize]:values", kNone),
      ROW(glPixelMapusv, "e:map i:mapsize H[mapsize]:values", kNone),
      ROW(glPixelMapuiv, "e:map i:mapsize U[mapsize]:values", kNone),
      ROW(glDrawPixels, "i:width i:height e:format e:type V{image width height}:pixels", kDraws),
      ROW(glReadPixels, "i:x i:y i:width i:height e:format e:type O{image width height}:pixels", kQuery),
      ROW(glCopyPixels, "i:x i:y i:width i:height e:type", kDraws),
      ROW(glBitmap, "i:width i:height f:xorig f:yorig f:xmove f:ymove B{bitmap width height}:bitmap", kDraws),
      // imaging: colour tables
      ROW(glColorTable, "e:target e:internalformat i:width e:format e:type V{image width}:table", kNone),
      ROW(glColorSubTable, "e:target i:start i:count e:format e:type V{image count}:data", kNone),
      ROW(glCopyColorTable, "e:target e:internalformat i:x i:y i:width", kNone),
      ROW(glColorTableParameterfv, "e:target e:pname F4:params", kNone),
      ROW(glGetColorTableParameteriv, "e:target e:pname Op:params", kQuery),
      ROW(glCopyColorSubTable, "e:target i:start i:x i:y i:width", kNone),
      STATE_QUERY_ROW(glGetColorTable, "e:target e:format e:type O{state}:table", color_table_elements),
      STATE_QUERY_ROW(glGetConvolutionFilter, "e:target e:format e:type O{state}:image", filter_elements),
      STATE_QUERY_ROW(glGetSeparableFilter, "e:target e:format e:type O{state}:row O{state}:column O{state}:span", separable_elements),
      ROW(glCopyConvolutionFilter1D, "e:target e:internalformat i:x i:y i:width", kNone),
      ROW(glConvolutionFilter1D, "e:target e:internalformat i:width e:format e:type V{image width}:image", kNone),
      ROW(glConvolutionFilter2D, "e:target e:internalformat i:width i:height e:format e:type V{image width height}:image", kNone),
      ROW(glSeparableFilter2D, "e:target e:internalformat i:width i:height e:format e:type V{image width}:row V{image height}:column", kNone),
      ROW(glCopyConvolutionFilter2D, "e:target e:internalformat i:x i:y i:width i:height", kNone),
      ROW(glConvolutionParameteri, "e:target e:pname x:params", kNone),
      ROW(glConvolutionParameterfv, "e:target e:pname Fp:params", kNone),
      ROW(glHistogram, "e:target i:width e:internalformat z:sink", kNone),
      ROW(glResetHistogram, "e:target", kNone),
      STATE_QUERY_ROW(glGetHistogram, "e:target z:reset e:format e:type O{state}:values", histogram_elements),
      ROW(glMinmax, "e:target e:internalformat z:sink", kNone),
      ROW(glResetMinmax, "e:target", kNone),
      STATE_QUERY_ROW(glGetMinmax, "e:target z:reset e:format e:type O{state}:values", minmax_elements),
      // fog
      ROW(glFogf, "e:pname y:param", kNone),
      ROW(glFogi, "e:pname x:param", kNone),
      ROW(glFogfv, "e:pname Fp:params", kNone),
      // passes (EXT_debug_marker)
      ROW(glPushGroupMarkerEXT, "i:length s:marker", kNotCompiled),
      ROW(glPopGroupMarkerEXT, "", kNotCompiled),
      ROW(glInsertEventMarkerEXT, "i:length s:marker", kNotCompiled),
  };
  return rows;
}

const std::unordered_map<std::string_view, const CallInfo*>& by_name() {
  static const std::unordered_map<std::string_view, const CallInfo*> map = [] {
    std::unordered_map<std::string_view, const CallInfo*> m;
    for (const CallInfo& c : table()) m.emplace(c.name, &c);
    return m;
  }();
  return map;
}

std::string format_float(double v, bool single) {
  if (single) return fmt::format("{}", static_cast<float>(v));
  return fmt::format("{}", v);
}

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (c == '\n') {
      out += "\\n";
    } else if (static_cast<unsigned char>(c) < 0x20) {
      out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string format_array(const Value& v) {
  std::string out = "{";
  const std::byte* p = v.bytes ? v.bytes->data() : nullptr;
  for (std::size_t k = 0; k < v.count; ++k) {
    if (k) out += ", ";
    auto read = [&](auto t) {
      decltype(t) x;
      std::memcpy(&x, p + k * sizeof(x), sizeof(x));
      return x;
    };
    switch (v.elem_type) {
      case GL_FLOAT: out += format_float(read(float{}), true); break;
      case GL_DOUBLE: out += format_float(read(double{}), false); break;
      case GL_INT: out += fmt::format("{}", read(std::int32_t{})); break;
      case GL_UNSIGNED_INT: out += fmt::format("{}", read(std::uint32_t{})); break;
      case GL_SHORT: out += fmt::format("{}", read(std::int16_t{})); break;
      case GL_UNSIGNED_SHORT: out += fmt::format("{}", read(std::uint16_t{})); break;
      case GL_BYTE: out += fmt::format("{}", read(std::int8_t{})); break;
      case GL_UNSIGNED_BYTE: out += fmt::format("{}", read(std::uint8_t{})); break;
      default: out += "?"; break;
    }
  }
  return out + "}";
}

}  // namespace

const CallInfo* find_call(std::string_view name) {
  auto it = by_name().find(name);
  return it == by_name().end() ? nullptr : it->second;
}

const CallInfo& call_info_or_die(std::string_view name) {
  const CallInfo* info = find_call(name);
  if (!info) {
    std::fprintf(stderr, "passim: internal error: no call-table row for %.*s\n", static_cast<int>(name.size()),
                 name.data());
    std::abort();
  }
  return *info;
}

const std::vector<const CallInfo*>& all_calls() {
  static const std::vector<const CallInfo*> list = [] {
    std::vector<const CallInfo*> v;
    for (const CallInfo& c : table()) v.push_back(&c);
    return v;
  }();
  return list;
}

int pname_count(GLenum pname) {
  switch (pname) {
    case GL_AMBIENT:
    case GL_DIFFUSE:
    case GL_SPECULAR:
    case GL_EMISSION:
    case GL_POSITION:
    case GL_AMBIENT_AND_DIFFUSE:
    case GL_LIGHT_MODEL_AMBIENT:
    case GL_TEXTURE_BORDER_COLOR:
    case GL_TEXTURE_ENV_COLOR:
    case GL_FOG_COLOR:
    case GL_CONVOLUTION_BORDER_COLOR:
    case GL_CONVOLUTION_FILTER_SCALE:
    case GL_CONVOLUTION_FILTER_BIAS:
    case GL_OBJECT_PLANE:
    case GL_EYE_PLANE:
      return 4;
    case GL_SPOT_DIRECTION:
    case GL_COLOR_INDEXES:
      return 3;
    case GL_SPOT_EXPONENT:
    case GL_SPOT_CUTOFF:
    case GL_CONSTANT_ATTENUATION:
    case GL_LINEAR_ATTENUATION:
    case GL_QUADRATIC_ATTENUATION:
    case GL_SHININESS:
    case GL_LIGHT_MODEL_LOCAL_VIEWER:
    case GL_LIGHT_MODEL_TWO_SIDE:
    case GL_LIGHT_MODEL_COLOR_CONTROL:
    case GL_TEXTURE_ENV_MODE:
    case GL_TEXTURE_GEN_MODE:
    case GL_FOG_MODE:
    case GL_CONVOLUTION_BORDER_MODE:
    case GL_FOG_DENSITY:
    case GL_FOG_START:
    case GL_FOG_END:
    case GL_FOG_INDEX:
    case GL_TEXTURE_MIN_FILTER:
    case GL_TEXTURE_MAG_FILTER:
    case GL_TEXTURE_WRAP_S:
    case GL_TEXTURE_WRAP_T:
    case GL_TEXTURE_WRAP_R:
    case GL_TEXTURE_MIN_LOD:
    case GL_TEXTURE_MAX_LOD:
    case GL_TEXTURE_BASE_LEVEL:
    case GL_TEXTURE_MAX_LEVEL:
    case GL_TEXTURE_PRIORITY:
    case GL_TEXTURE_COMPARE_SGIX:
    case GL_TEXTURE_COMPARE_OPERATOR_SGIX:
    case GL_SHADOW_AMBIENT_SGIX:
    case GL_TEXTURE_COMPARE_MODE:
    case GL_TEXTURE_COMPARE_FUNC:
    case GL_DEPTH_TEXTURE_MODE:
      return 1;
    default:
      return 0;
  }
}

IntegerRange integer_range(char kind) {
  using L = std::numeric_limits<std::int32_t>;
  switch (kind) {
    case 'i': return {L::min(), L::max()};  // GLint
    case 'x': return {L::min(), std::numeric_limits<std::uint32_t>::max()};  // GLint or an enum
    case 'c': case 'z': return {0, 255};  // GLubyte, GLboolean
    case 'g': return {-128, 127};  // GLbyte
    case 'h': return {-32768, 32767};  // GLshort
    case 'w': return {0, 65535};  // GLushort
    default: return {0, std::numeric_limits<std::uint32_t>::max()};  // GLuint, GLenum, GLbitfield
  }
}

int type_size(GLenum type) {
  switch (type) {
    case GL_BYTE:
    case GL_UNSIGNED_BYTE:
      return 1;
    case GL_SHORT:
    case GL_UNSIGNED_SHORT:
      return 2;
    case GL_INT:
    case GL_UNSIGNED_INT:
    case GL_FLOAT:
      return 4;
    case GL_DOUBLE:
      return 8;
    default:
      return 0;
  }
}

std::string describe_call(const CallInfo& info) {
  auto type_of = [](char kind) -> std::string_view {
    switch (kind) {
      case 'e': case 'n': case 'm': return "GLenum";
      case 'z': return "GLboolean";
      case 'b': case 'k': return "GLbitfield";
      case 'i': return "GLint";
      case 'x': return "GLint(or enum)";
      case 'u': return "GLuint";
      case 'c': return "GLubyte";
      case 'g': return "GLbyte";
      case 'h': return "GLshort";
      case 'w': return "GLushort";
      case 'f': return "GLfloat";
      case 'y': return "GLfloat(or enum)";
      case 'd': return "GLdouble";
      case 's': return "string";
      case 'F': return "const GLfloat*";
      case 'D': return "const GLdouble*";
      case 'I': return "const GLint*";
      case 'U': return "const GLuint*";
      case 'B': return "const GLubyte*";
      case 'G': return "const GLbyte*";
      case 'S': return "const GLshort*";
      case 'H': return "const GLushort*";
      case 'V': return "const void*";
      case 'O': return "out";
      default: return "?";
    }
  };
  std::string out = fmt::format("{}(", info.name);
  for (std::size_t k = 0; k < info.params.size(); ++k) {
    const CallInfo::Param& p = info.params[k];
    out += fmt::format("{}{} {}", k ? ", " : "", type_of(p.kind), p.name);
    auto arg = [&](int i) { return i < 0 ? std::string_view("1") : info.params[static_cast<std::size_t>(i)].name; };
    switch (p.length) {
      case Length::Fixed: out += fmt::format("[{}]", p.fixed_count); break;
      case Length::ByPname: out += "[by pname]"; break;
      case Length::ByArgument: out += fmt::format("[{}]", arg(p.count_arg)); break;
      case Length::Image:
        out += fmt::format("[image {}", arg(p.dims[0]));
        for (int d : {p.dims[1], p.dims[2]})
          if (d >= 0) out += fmt::format("x{}", arg(d));
        out += "]";
        break;
      case Length::Bitmap: out += fmt::format("[bitmap {}x{}]", arg(p.dims[0]), arg(p.dims[1])); break;
      case Length::Any: if (p.kind != 'O') out += "[read at each draw]"; break;
      case Length::State: out += "[as the GL's state sizes it]"; break;
      case Length::None: break;
    }
  }
  out += ")";
  std::vector<std::string> notes;
  if (info.query) notes.push_back("query");
  else if (!info.compiled_into_lists) notes.push_back("not compiled into lists");
  if (info.allowed_in_begin_end) notes.push_back("allowed in Begin/End");
  if (info.draws) notes.push_back("draws");
  if (!notes.empty()) out += fmt::format("  [{}]", fmt::join(notes, ", "));
  return out;
}

std::string format_call(const Call& call) {
  const CallInfo& info = *call.info;
  std::string out(info.name);
  out += '(';
  for (std::size_t k = 0; k < call.args.size(); ++k) {
    if (k) out += ", ";
    const Value& v = call.args[k];
    switch (info.params[k].kind) {
      case 'e': out += enum_name(static_cast<std::uint32_t>(v.i)); break;
      case 'm': out += enum_name(static_cast<std::uint32_t>(v.i), EnumRole::PrimitiveMode); break;
      case 'n': out += enum_name(static_cast<std::uint32_t>(v.i), EnumRole::Buffer); break;
      case 'z': out += enum_name(static_cast<std::uint32_t>(v.i), EnumRole::Boolean); break;
      case 'b': out += bitfield_name(static_cast<std::uint32_t>(v.i)); break;
      case 'k': out += client_bitfield_name(static_cast<std::uint32_t>(v.i)); break;
      case 'i':
      case 'u':
      case 'c':
      case 'g':
      case 'h':
      case 'w': out += fmt::format("{}", v.i); break;
      case 'x': {
        std::string name = v.i > 0xFF ? enum_name(static_cast<std::uint32_t>(v.i)) : "";
        out += (!name.empty() && name[0] == 'G') ? name : fmt::format("{}", v.i);
        break;
      }
      case 'y': {
        double d = v.d;
        bool enum_like = d > 255.0 && d < 65536.0 && d == static_cast<double>(static_cast<std::int64_t>(d));
        std::string name = enum_like ? enum_name(static_cast<std::uint32_t>(d)) : "";
        out += (!name.empty() && name[0] == 'G') ? name : format_float(d, true);
        break;
      }
      case 'f': out += format_float(v.d, true); break;
      case 'd': out += format_float(v.d, false); break;
      case 's': out += quote(v.str()); break;
      case 'O': out += "{}"; break;
      default: out += format_array(v); break;
    }
  }
  out += ')';
  return out;
}

namespace detail {
Value array_value(const void* data, GLenum type, std::size_t count) {
  Value v;
  v.elem_type = type;
  v.count = data ? count : 0;
  std::size_t bytes = v.count * static_cast<std::size_t>(type_size(type));
  auto buf = std::make_shared<std::vector<std::byte>>(bytes);
  if (bytes) std::memcpy(buf->data(), data, bytes);
  v.bytes = std::move(buf);
  return v;
}
}  // namespace detail

int CallInfo::param_index(std::string_view n) const {
  for (std::size_t k = 0; k < params.size(); ++k)
    if (params[k].name == n) return static_cast<int>(k);
  return -1;
}

GLenum param_element_type(const CallInfo& info, std::size_t index, const std::vector<Value>& done) {
  const CallInfo::Param& p = info.params[index];
  switch (p.kind) {
    case 'F': return GL_FLOAT;
    case 'D': return GL_DOUBLE;
    case 'I': return GL_INT;
    case 'U': return GL_UNSIGNED_INT;
    case 'B': return GL_UNSIGNED_BYTE;
    case 'G': return GL_BYTE;
    case 'S': return GL_SHORT;
    case 'H': return GL_UNSIGNED_SHORT;
    case 'V':
    case 'O':
      if (p.type_arg >= 0 && static_cast<std::size_t>(p.type_arg) < done.size())
        return static_cast<GLenum>(done[static_cast<std::size_t>(p.type_arg)].i);
      return p.kind == 'O' ? GL_UNSIGNED_BYTE : 0;
    default: return 0;
  }
}

std::uint64_t param_elements_needed(const CallInfo& info, std::size_t index, const std::vector<Value>& done,
                                    const PixelStore& store) {
  const CallInfo::Param& p = info.params[index];
  auto arg = [&](int k) { return k < 0 ? std::int64_t{1} : done[static_cast<std::size_t>(k)].i; };
  auto dimension = [&](int k) {
    const std::int64_t v = arg(k);
    return v > std::numeric_limits<int>::max() ? -1 : static_cast<int>(v);  // too large: rejected by the GL
  };
  switch (p.length) {
    case Length::Fixed: return static_cast<std::uint64_t>(p.fixed_count);
    case Length::ByPname:
      // An unknown pname still reads one value.
      return static_cast<std::uint64_t>(std::max(pname_count(static_cast<GLenum>(arg(p.count_arg))), 1));
    case Length::ByArgument: return static_cast<std::uint64_t>(std::max<std::int64_t>(arg(p.count_arg), 0));
    case Length::Image: {
      const GLenum format = static_cast<GLenum>(arg(p.format_arg)), type = static_cast<GLenum>(arg(p.type_arg));
      const int w = dimension(p.dims[0]), h = dimension(p.dims[1]), d = dimension(p.dims[2]);
      if (format_components(format) == 0 || !is_pixel_type(type) || w <= 0 || h <= 0 || d <= 0) return 0;
      // A 3D image is `d` images of h rows (§3.8.1; no image-height mode modelled yet).
      const CheckedSize rows = CheckedSize(h) * d;
      if (!rows.fits_int()) throw SizeOverflow("an image of more than 2^31 rows");
      const CheckedSize bytes = image_bytes(w, static_cast<int>(rows.value()), format, type, store);
      return bytes.value() / static_cast<std::uint64_t>(type_size(type));
    }
    case Length::Bitmap: {
      const int w = dimension(p.dims[0]), h = dimension(p.dims[1]);
      return w <= 0 || h <= 0 ? 0 : bitmap_bytes(w, h, store);
    }
    case Length::None:
    case Length::Any:
    case Length::State: return 0;  // output sizes: output_elements_needed
  }
  return 0;
}

std::uint64_t output_elements_needed(const CallInfo& info, std::size_t index, const std::vector<Value>& done,
                                     const Context& ctx) {
  const CallInfo::Param& p = info.params[index];
  if (p.length == Length::State) return info.state_elements(ctx, done, index);
  // Images are packed under the pack modes (§4.3.2).
  return param_elements_needed(info, index, done, ctx.pack_store());
}

bool CallInfo::has_outputs() const {
  return std::any_of(params.begin(), params.end(), [](const Param& p) { return p.kind == 'O'; });
}

void run_collecting(const CallInfo& info, Context& ctx, std::span<const Value> args, CallResults& results) {
  struct Collecting {
    explicit Collecting(CallResults& r) : previous(collecting) { collecting = &r; }
    ~Collecting() { collecting = previous; }
    CallResults* previous;
  } scope(results);
  info.invoke(ctx, args);
}

bool param_may_be_null(const CallInfo::Param& p) { return p.length == Length::Image || p.length == Length::Bitmap; }

}  // namespace passim
