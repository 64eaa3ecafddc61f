// The call table (see calls.hpp). One row per GL entry point.
#include "pipeline/calls.hpp"

#include <algorithm>

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unordered_map>

#include "pipeline/context.hpp"

namespace passim {
namespace {

// Output scratch for query calls replayed from a trace.
template <class T>
T* output_scratch() {
  if constexpr (std::is_void_v<T>) {
    return output_scratch<std::byte>();
  } else {
    static thread_local T buffer[65536];
    return buffer;
  }
}

template <class T>
T arg(const Value& v) {
  if constexpr (std::is_same_v<T, const char*>) {
    return v.str().c_str();
  } else if constexpr (std::is_pointer_v<T> && std::is_const_v<std::remove_pointer_t<T>>) {
    return v.bytes ? reinterpret_cast<T>(v.bytes->data()) : nullptr;
  } else if constexpr (std::is_pointer_v<T>) {
    return static_cast<T>(output_scratch<std::remove_pointer_t<T>>());
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
    (c.*MF)(arg<A>(v[I])...);
  }
  static constexpr std::size_t arity = sizeof...(A);
  static constexpr bool returns = !std::is_void_v<R>;
};

enum Flags : unsigned {
  kNone = 0,
  kNotCompiled = 1,    // §5.4: executed immediately, never put in a list
  kInBeginEnd = 2,     // §2.6.3: allowed between Begin and End
  kQuery = 4,          // output arguments
  kRecordAtDraw = 8,   // pointer set-up: recorded with the data at each draw
};

std::vector<CallInfo::Param> parse_signature(std::string_view sig) {
  std::vector<CallInfo::Param> params;
  for (std::size_t i = 0; i < sig.size(); ++i) {
    CallInfo::Param p{sig[i], 0, 0};
    if (std::strchr("FDIUBVH", sig[i])) {
      char next = i + 1 < sig.size() ? sig[i + 1] : 0;
      if (next == 'p' || next == '*') {
        p.count_rule = next;
        ++i;
      } else {
        p.count_rule = 'n';
        while (i + 1 < sig.size() && sig[i + 1] >= '0' && sig[i + 1] <= '9') {
          p.fixed_count = p.fixed_count * 10 + (sig[i + 1] - '0');
          ++i;
        }
      }
    }
    params.push_back(p);
  }
  return params;
}

template <auto MF>
CallInfo row(std::string_view name, std::string_view sig, unsigned flags) {
  CallInfo info;
  info.name = name;
  info.signature = sig;
  info.compiled_into_lists = !(flags & (kNotCompiled | kQuery));
  info.allowed_in_begin_end = flags & kInBeginEnd;
  info.keeps_raster_queue = info.allowed_in_begin_end || name == "glBegin" || name == "glDrawArrays" ||
                            name == "glDrawElements" || name.starts_with("glRect");
  info.query = flags & kQuery;
  info.recorded_at_draw = flags & kRecordAtDraw;
  info.invoke = &Invoker<MF>::call;
  info.returns_value = Invoker<MF>::returns;
  info.params = parse_signature(sig);
  if (info.params.size() != Invoker<MF>::arity) {
    std::fprintf(stderr, "passim: internal error: signature of %.*s has %zu letters for %zu parameters\n",
                 static_cast<int>(name.size()), name.data(), info.params.size(), Invoker<MF>::arity);
    std::abort();
  }
  return info;
}

#define ROW(fn, sig, flags) row<&Context::fn>(#fn, sig, flags)

const std::vector<CallInfo>& table() {
  static const std::vector<CallInfo> rows = {
      // errors and state
      ROW(glGetError, "", kNotCompiled),
      ROW(glEnable, "e", kNone),
      ROW(glDisable, "e", kNone),
      ROW(glIsEnabled, "e", kNotCompiled),
      ROW(glGetIntegerv, "eO", kQuery),
      ROW(glGetFloatv, "eO", kQuery),
      ROW(glGetDoublev, "eO", kQuery),
      ROW(glGetBooleanv, "eO", kQuery),
      ROW(glHint, "ee", kNone),
      ROW(glFlush, "", kNotCompiled),
      ROW(glFinish, "", kNotCompiled),
      // framebuffer control
      ROW(glClear, "b", kNone),
      ROW(glClearColor, "ffff", kNone),
      ROW(glClearDepth, "d", kNone),
      ROW(glClearStencil, "i", kNone),
      ROW(glClearAccum, "ffff", kNone),
      ROW(glAccum, "ef", kNone),
      ROW(glColorMask, "zzzz", kNone),
      ROW(glDepthMask, "z", kNone),
      ROW(glStencilMask, "u", kNone),
      ROW(glDrawBuffer, "n", kNone),
      ROW(glReadBuffer, "n", kNone),
      // per-fragment operations
      ROW(glScissor, "iiii", kNone),
      ROW(glAlphaFunc, "ef", kNone),
      ROW(glStencilFunc, "eiu", kNone),
      ROW(glStencilOp, "eee", kNone),
      ROW(glDepthFunc, "e", kNone),
      ROW(glBlendFunc, "ee", kNone),
      ROW(glBlendEquation, "e", kNone),
      ROW(glBlendColor, "ffff", kNone),
      ROW(glLogicOp, "e", kNone),
      // transformation
      ROW(glViewport, "iiii", kNone),
      ROW(glDepthRange, "dd", kNone),
      ROW(glMatrixMode, "e", kNone),
      ROW(glLoadIdentity, "", kNone),
      ROW(glLoadMatrixf, "F16", kNone),
      ROW(glLoadMatrixd, "D16", kNone),
      ROW(glMultMatrixf, "F16", kNone),
      ROW(glMultMatrixd, "D16", kNone),
      ROW(glPushMatrix, "", kNone),
      ROW(glPopMatrix, "", kNone),
      ROW(glTranslatef, "fff", kNone),
      ROW(glTranslated, "ddd", kNone),
      ROW(glRotatef, "ffff", kNone),
      ROW(glRotated, "dddd", kNone),
      ROW(glScalef, "fff", kNone),
      ROW(glScaled, "ddd", kNone),
      ROW(glFrustum, "dddddd", kNone),
      ROW(glOrtho, "dddddd", kNone),
      ROW(glClipPlane, "eD4", kNone),
      ROW(gluPerspective, "dddd", kNone),
      ROW(gluLookAt, "ddddddddd", kNone),
      // vertices
      ROW(glRectf, "ffff", kNone),
      ROW(glRectd, "dddd", kNone),
      ROW(glRecti, "iiii", kNone),
      ROW(glBegin, "m", kNone),
      ROW(glEnd, "", kInBeginEnd),
      ROW(glVertex2f, "ff", kInBeginEnd),
      ROW(glVertex3f, "fff", kInBeginEnd),
      ROW(glVertex4f, "ffff", kInBeginEnd),
      ROW(glVertex2d, "dd", kInBeginEnd),
      ROW(glVertex3d, "ddd", kInBeginEnd),
      ROW(glVertex4d, "dddd", kInBeginEnd),
      ROW(glVertex2i, "ii", kInBeginEnd),
      ROW(glVertex3i, "iii", kInBeginEnd),
      ROW(glVertex2fv, "F2", kInBeginEnd),
      ROW(glVertex2dv, "D2", kInBeginEnd),
      ROW(glVertex3dv, "D3", kInBeginEnd),
      ROW(glVertex2iv, "I2", kInBeginEnd),
      ROW(glVertex3iv, "I3", kInBeginEnd),
      ROW(glNormal3dv, "D3", kInBeginEnd),
      ROW(glColor3ubv, "B3", kInBeginEnd),
      ROW(glColor4ubv, "B4", kInBeginEnd),
      ROW(glColor3dv, "D3", kInBeginEnd),
      ROW(glColor4dv, "D4", kInBeginEnd),
      ROW(glTexCoord2d, "dd", kInBeginEnd),
      ROW(glTexCoord2i, "ii", kInBeginEnd),
      ROW(glTexCoord2dv, "D2", kInBeginEnd),
      ROW(glTexCoord3fv, "F3", kInBeginEnd),
      ROW(glTexCoord4fv, "F4", kInBeginEnd),
      ROW(glVertex3fv, "F3", kInBeginEnd),
      ROW(glVertex4fv, "F4", kInBeginEnd),
      ROW(glNormal3f, "fff", kInBeginEnd),
      ROW(glNormal3d, "ddd", kInBeginEnd),
      ROW(glNormal3fv, "F3", kInBeginEnd),
      ROW(glColor3f, "fff", kInBeginEnd),
      ROW(glColor4f, "ffff", kInBeginEnd),
      ROW(glColor3d, "ddd", kInBeginEnd),
      ROW(glColor4d, "dddd", kInBeginEnd),
      ROW(glColor3ub, "ccc", kInBeginEnd),
      ROW(glColor4ub, "cccc", kInBeginEnd),
      ROW(glColor3fv, "F3", kInBeginEnd),
      ROW(glColor4fv, "F4", kInBeginEnd),
      ROW(glTexCoord1f, "f", kInBeginEnd),
      ROW(glTexCoord2f, "ff", kInBeginEnd),
      ROW(glTexCoord3f, "fff", kInBeginEnd),
      ROW(glTexCoord4f, "ffff", kInBeginEnd),
      ROW(glTexCoord4d, "dddd", kInBeginEnd),
      ROW(glTexCoord2fv, "F2", kInBeginEnd),
      // vertex arrays
      ROW(glEnableClientState, "e", kNotCompiled),
      ROW(glDisableClientState, "e", kNotCompiled),
      ROW(glVertexPointer, "ieiV*", kNotCompiled | kRecordAtDraw),
      ROW(glNormalPointer, "eiV*", kNotCompiled | kRecordAtDraw),
      ROW(glColorPointer, "ieiV*", kNotCompiled | kRecordAtDraw),
      ROW(glTexCoordPointer, "ieiV*", kNotCompiled | kRecordAtDraw),
      ROW(glArrayElement, "i", kInBeginEnd),
      ROW(glDrawArrays, "mii", kNone),
      ROW(glDrawElements, "mieV*", kNone),
      // display lists
      ROW(glNewList, "ue", kNotCompiled),
      ROW(glEndList, "", kNotCompiled),
      ROW(glCallList, "u", kInBeginEnd),
      ROW(glCallLists, "ieV*", kInBeginEnd),
      ROW(glGenLists, "i", kNotCompiled),
      ROW(glDeleteLists, "ui", kNotCompiled),
      ROW(glIsList, "u", kNotCompiled),
      ROW(glListBase, "u", kNone),
      // lighting
      ROW(glShadeModel, "e", kNone),
      ROW(glLightf, "eef", kNone),
      ROW(glLighti, "eei", kNone),
      ROW(glLightfv, "eeFp", kNone),
      ROW(glLightModelf, "ey", kNone),
      ROW(glLightModeli, "ex", kNone),
      ROW(glLightModelfv, "eFp", kNone),
      ROW(glMaterialf, "eef", kInBeginEnd),
      ROW(glMaterialfv, "eeFp", kInBeginEnd),
      ROW(glColorMaterial, "ee", kNone),
      // rasterization
      ROW(glCullFace, "e", kNone),
      ROW(glFrontFace, "e", kNone),
      ROW(glPolygonMode, "ee", kNone),
      ROW(glPolygonOffset, "ff", kNone),
      ROW(glPointSize, "f", kNone),
      ROW(glLineWidth, "f", kNone),
      // pixel storage and textures
      ROW(glPixelStorei, "ex", kNotCompiled),
      ROW(glPixelStoref, "ey", kNotCompiled),
      ROW(glGenTextures, "iO", kNotCompiled),
      ROW(glDeleteTextures, "iU*", kNotCompiled),
      ROW(glBindTexture, "eu", kNone),
      ROW(glIsTexture, "u", kNotCompiled),
      ROW(glTexImage1D, "eixiieeV*", kNone),
      ROW(glTexImage2D, "eixiiieeV*", kNone),
      ROW(gluBuild1DMipmaps, "exieeV*", kNone),
      ROW(gluBuild2DMipmaps, "exiieeV*", kNone),
      ROW(glTexSubImage1D, "eiiieeV*", kNone),
      ROW(glTexSubImage2D, "eiiiiieeV*", kNone),
      ROW(glCopyTexImage1D, "eieiiii", kNone),
      ROW(glCopyTexImage2D, "eieiiiii", kNone),
      ROW(glCopyTexSubImage1D, "eiiiii", kNone),
      ROW(glCopyTexSubImage2D, "eiiiiiii", kNone),
      ROW(glGetTexImage, "eieeO", kQuery),
      ROW(glTexParameteri, "eex", kNone),
      ROW(glTexParameterf, "eey", kNone),
      ROW(glTexParameterfv, "eeFp", kNone),
      ROW(glGetTexParameterfv, "eeO", kQuery),
      ROW(glGetTexParameteriv, "eeO", kQuery),
      ROW(glGetTexLevelParameteriv, "eieO", kQuery),
      ROW(glTexEnvi, "eex", kNone),
      ROW(glTexEnvf, "eey", kNone),
      ROW(glTexEnvfv, "eeFp", kNone),
      ROW(glTexGeni, "eex", kNone),
      ROW(glTexGenf, "eey", kNone),
      ROW(glTexGenfv, "eeFp", kNone),
      ROW(glTexGendv, "eeDp", kNone),
      // raster position and pixel rectangles
      ROW(glRasterPos2i, "ii", kNone),
      ROW(glRasterPos2f, "ff", kNone),
      ROW(glRasterPos3f, "fff", kNone),
      ROW(glRasterPos4f, "ffff", kNone),
      ROW(glRasterPos2d, "dd", kNone),
      ROW(glRasterPos3d, "ddd", kNone),
      ROW(glPixelZoom, "ff", kNone),
      ROW(glPixelTransferf, "ey", kNone),
      ROW(glPixelTransferi, "ex", kNone),
      ROW(glPixelMapfv, "eiF*", kNone),
      ROW(glPixelMapusv, "eiH*", kNone),
      ROW(glPixelMapuiv, "eiU*", kNone),
      ROW(glDrawPixels, "iieeV*", kNone),
      ROW(glReadPixels, "iiiieeO", kQuery),
      ROW(glCopyPixels, "iiiie", kNone),
      ROW(glBitmap, "iiffffB*", kNone),
      // imaging: colour tables
      ROW(glColorTable, "eeieeV*", kNone),
      ROW(glColorSubTable, "eiieeV*", kNone),
      ROW(glCopyColorTable, "eeiii", kNone),
      ROW(glColorTableParameterfv, "eeF4", kNone),
      ROW(glGetColorTableParameteriv, "eeO", kQuery),
      ROW(glCopyColorSubTable, "eiiii", kNone),
      ROW(glGetColorTable, "eeeO", kQuery),
      ROW(glGetConvolutionFilter, "eeeO", kQuery),
      ROW(glGetSeparableFilter, "eeeOOO", kQuery),
      ROW(glCopyConvolutionFilter1D, "eeiii", kNone),
      ROW(glConvolutionFilter1D, "eeieeV*", kNone),
      ROW(glConvolutionFilter2D, "eeiieeV*", kNone),
      ROW(glSeparableFilter2D, "eeiieeV*V*", kNone),
      ROW(glCopyConvolutionFilter2D, "eeiiii", kNone),
      ROW(glConvolutionParameteri, "eex", kNone),
      ROW(glConvolutionParameterfv, "eeFp", kNone),
      ROW(glHistogram, "eiez", kNone),
      ROW(glResetHistogram, "e", kNone),
      ROW(glGetHistogram, "ezeeO", kQuery),
      ROW(glMinmax, "eez", kNone),
      ROW(glResetMinmax, "e", kNone),
      ROW(glGetMinmax, "ezeeO", kQuery),
      // fog
      ROW(glFogf, "ey", kNone),
      ROW(glFogi, "ex", kNone),
      ROW(glFogfv, "eFp", kNone),
      // passes (EXT_debug_marker)
      ROW(glPushGroupMarkerEXT, "is", kNotCompiled),
      ROW(glPopGroupMarkerEXT, "", kNotCompiled),
      ROW(glInsertEventMarkerEXT, "is", kNotCompiled),
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
      case 'i':
      case 'u':
      case 'c': out += fmt::format("{}", v.i); break;
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

GLenum param_element_type(const CallInfo& info, std::size_t index, const std::vector<Value>& done) {
  switch (info.params[index].kind) {
    case 'F': return GL_FLOAT;
    case 'D': return GL_DOUBLE;
    case 'I': return GL_INT;
    case 'U': return GL_UNSIGNED_INT;
    case 'B': return GL_UNSIGNED_BYTE;
    case 'H': return GL_UNSIGNED_SHORT;
    case 'V':
      for (std::size_t k = index; k-- > 0;)
        if (info.params[k].kind == 'e') return static_cast<GLenum>(done[k].i);
      return 0;
    default: return 0;
  }
}

std::size_t param_values_needed(const CallInfo& info, std::size_t index, const std::vector<Value>& done) {
  const CallInfo::Param& p = info.params[index];
  if (p.count_rule == 'n') return static_cast<std::size_t>(p.fixed_count);
  if (p.count_rule != 'p') return 0;
  for (std::size_t k = index; k-- > 0;)
    if (info.params[k].kind == 'e')
      // An unknown pname still reads one value.
      return std::max<std::size_t>(static_cast<std::size_t>(pname_count(static_cast<GLenum>(done[k].i))), 1);
  return 1;
}

}  // namespace passim
