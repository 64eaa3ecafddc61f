// Context: vertex arrays (§2.8).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <optional>
#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_internal.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/clipping.hpp"
#include "stages/lighting.hpp"
#include "stages/rasterizer.hpp"

namespace passim {

// ---------------------------------------------------------------- vertex arrays (§2.8)

namespace {
ClientArray* array_of(ClientArrayState& s, GLenum a) {
  switch (a) {
    case GL_VERTEX_ARRAY: return &s.vertex;
    case GL_NORMAL_ARRAY: return &s.normal;
    case GL_COLOR_ARRAY: return &s.color;
    case GL_TEXTURE_COORD_ARRAY: return &s.texcoord;
    case GL_EDGE_FLAG_ARRAY: return &s.edge_flag;
    default: return nullptr;
  }
}
bool is_array_type(GLenum type, bool allow_unsigned, bool allow_byte) {
  switch (type) {
    case GL_SHORT: case GL_INT: case GL_FLOAT: case GL_DOUBLE: return true;
    case GL_BYTE: return allow_byte;
    case GL_UNSIGNED_BYTE: case GL_UNSIGNED_SHORT: case GL_UNSIGNED_INT: return allow_unsigned;
    default: return false;
  }
}
}  // namespace

void Context::glEnableClientState(GLenum array) {
  PASSIM_ENTRY(array)
  ClientArray* a = array_of(arrays_, array);
  if (!a) return set_error(GL_INVALID_ENUM);
  a->enabled = true;
}

void Context::glDisableClientState(GLenum array) {
  PASSIM_ENTRY(array)
  ClientArray* a = array_of(arrays_, array);
  if (!a) return set_error(GL_INVALID_ENUM);
  a->enabled = false;
}

#define PASSIM_SET_POINTER(member, size_, type_, stride_, ptr_) \
  arrays_.member.size = (size_);                                 \
  arrays_.member.type = (type_);                                 \
  arrays_.member.stride = (stride_);                             \
  arrays_.member.pointer = (ptr_);                               \
  arrays_.member.extent = SIZE_MAX;

void Context::glVertexPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (size < 2 || size > 4 || stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, false, false)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(vertex, size, type, stride, pointer)
}

void Context::glNormalPointer(GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, false, true)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(normal, 3, type, stride, pointer)
}

void Context::glColorPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (size < 3 || size > 4 || stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, true, true)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(color, size, type, stride, pointer)
}

void Context::glTexCoordPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (size < 1 || size > 4 || stride < 0) return set_error(GL_INVALID_VALUE);
  if (!is_array_type(type, false, false)) return set_error(GL_INVALID_ENUM);
  PASSIM_SET_POINTER(texcoord, size, type, stride, pointer)
}

void Context::glEdgeFlagPointer(GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  if (stride < 0) return set_error(GL_INVALID_VALUE);
  PASSIM_SET_POINTER(edge_flag, 1, GL_UNSIGNED_BYTE, stride, pointer)
}
#undef PASSIM_SET_POINTER

namespace {
// §2.8, Table 2.5: an interleaved format's arrays. Sizes are components (0: the array is
// disabled); offsets and the stride are in bytes, as the table gives them with f the size of
// a float and c that of four unsigned bytes rounded up to a multiple of f (4 both).
struct InterleavedLayout {
  int st = 0, sc = 0, sv = 0;  // texture coordinates, colour, vertex components
  bool en = false;             // a normal
  GLenum tc = GL_FLOAT;        // the colour's type
  int pc = 0, pn = 0, pv = 0, s = 0;
};
std::optional<InterleavedLayout> interleaved_layout(GLenum format) {
  InterleavedLayout l;
  switch (format) {
    case GL_V2F: l.sv = 2; break;
    case GL_V3F: l.sv = 3; break;
    case GL_C4UB_V2F: l.sc = 4; l.tc = GL_UNSIGNED_BYTE; l.sv = 2; break;
    case GL_C4UB_V3F: l.sc = 4; l.tc = GL_UNSIGNED_BYTE; l.sv = 3; break;
    case GL_C3F_V3F: l.sc = 3; l.sv = 3; break;
    case GL_N3F_V3F: l.en = true; l.sv = 3; break;
    case GL_C4F_N3F_V3F: l.sc = 4; l.en = true; l.sv = 3; break;
    case GL_T2F_V3F: l.st = 2; l.sv = 3; break;
    case GL_T4F_V4F: l.st = 4; l.sv = 4; break;
    case GL_T2F_C4UB_V3F: l.st = 2; l.sc = 4; l.tc = GL_UNSIGNED_BYTE; l.sv = 3; break;
    case GL_T2F_C3F_V3F: l.st = 2; l.sc = 3; l.sv = 3; break;
    case GL_T2F_N3F_V3F: l.st = 2; l.en = true; l.sv = 3; break;
    case GL_T2F_C4F_N3F_V3F: l.st = 2; l.sc = 4; l.en = true; l.sv = 3; break;
    case GL_T4F_C4F_N3F_V4F: l.st = 4; l.sc = 4; l.en = true; l.sv = 4; break;
    default: return std::nullopt;
  }
  constexpr int f = sizeof(GLfloat), c = 4;
  // The table's offsets: texture coordinates first, then colour, normal and vertex.
  l.pc = l.st * f;
  l.pn = l.pc + (l.sc == 0 ? 0 : l.tc == GL_UNSIGNED_BYTE ? c : l.sc * f);
  l.pv = l.pn + (l.en ? 3 * f : 0);
  l.s = l.pv + l.sv * f;
  return l;
}
}  // namespace

void Context::glInterleavedArrays(GLenum format, GLsizei stride, const void* pointer) {
  PASSIM_ENTRY()
  const std::optional<InterleavedLayout> l = interleaved_layout(format);
  if (!l) return set_error(GL_INVALID_ENUM);
  if (stride < 0) return set_error(GL_INVALID_VALUE);
  // §2.8: the equivalent of these calls (the index array is not modelled).
  const GLsizei str = stride == 0 ? l->s : stride;
  const auto* base = static_cast<const std::byte*>(pointer);
  auto at = [&](int offset) -> const void* { return base ? base + offset : nullptr; };
  const std::array<std::pair<GLenum, bool>, 5> enables{{{GL_EDGE_FLAG_ARRAY, false},
                                                        {GL_TEXTURE_COORD_ARRAY, l->st > 0},
                                                        {GL_COLOR_ARRAY, l->sc > 0},
                                                        {GL_NORMAL_ARRAY, l->en},
                                                        {GL_VERTEX_ARRAY, true}}};
  for (const auto& [array, on] : enables) {
    if (on) glEnableClientState(array);
    else glDisableClientState(array);
  }
  if (l->st > 0) glTexCoordPointer(l->st, GL_FLOAT, str, at(0));
  if (l->sc > 0) glColorPointer(l->sc, l->tc, str, at(l->pc));
  if (l->en) glNormalPointer(GL_FLOAT, str, at(l->pn));
  glVertexPointer(l->sv, GL_FLOAT, str, at(l->pv));
  // The call itself is recorded as its pointer calls at each draw (record_client_arrays); the
  // enables it changed are recorded now.
  if (sink_ && passim_call_scope_.outermost()) {
    for (const auto& [array, on] : enables) {
      static const CallInfo& enable = call_info_or_die("glEnableClientState");
      static const CallInfo& disable = call_info_or_die("glDisableClientState");
      Value cap;
      cap.i = array;
      sink_->on_call(Call{on ? &enable : &disable, {cap}});
    }
  }
}

Vec4 Context::array_value_at(const ClientArray& a, int i, bool normalise) const {
  // Reads element i; with `normalise`, integer components map to [0,1] or [-1,1] (Table 2.6).
  const int ts = type_size(a.type);
  const std::size_t stride = a.stride ? static_cast<std::size_t>(a.stride) : static_cast<std::size_t>(ts * a.size);
  const std::byte* p = static_cast<const std::byte*>(a.pointer) + stride * static_cast<std::size_t>(i);
  Vec4 out(0.0, 0.0, 0.0, 1.0);
  for (int k = 0; k < a.size; ++k) {
    const std::byte* e = p + k * ts;
    auto read = [&](auto x) {
      std::memcpy(&x, e, sizeof x);
      return normalise ? normalized_component(x) : static_cast<double>(x);
    };
    switch (a.type) {
      case GL_FLOAT: out[k] = read(float{}); break;
      case GL_DOUBLE: out[k] = read(double{}); break;
      case GL_INT: out[k] = read(std::int32_t{}); break;
      case GL_UNSIGNED_INT: out[k] = read(std::uint32_t{}); break;
      case GL_SHORT: out[k] = read(std::int16_t{}); break;
      case GL_UNSIGNED_SHORT: out[k] = read(std::uint16_t{}); break;
      case GL_BYTE: out[k] = read(std::int8_t{}); break;
      case GL_UNSIGNED_BYTE: out[k] = read(std::uint8_t{}); break;
      default: out[k] = 0.0; break;
    }
  }
  return out;
}

void Context::check_array_bounds(std::int64_t max_index) const {
  auto check = [&](const ClientArray& a, const char* name) {
    if (!a.enabled) return;
    // An enabled array without a pointer: undefined in GL (a crash on real drivers).
    if (!a.pointer)
      throw ClientDataError(fmt::format("{} draws with the {} array enabled but no {} pointer given", current_call_,
                                        name, name));
    if (a.extent == SIZE_MAX) return;
    const CheckedSize elem = CheckedSize(type_size(a.type)) * a.size;
    const CheckedSize stride = a.stride ? CheckedSize(a.stride) : elem;
    bool inside = max_index >= 0 && max_index <= std::numeric_limits<int>::max();
    try {
      inside = inside && CheckedSize(max_index) * stride + elem <= CheckedSize(a.extent);
    } catch (const SizeOverflow&) {
      inside = false;
    }
    if (!inside)
      throw ClientDataError(fmt::format("{} reads element {} of the {} array, but only {} bytes were given",
                                        current_call_, max_index, name, a.extent));
  };
  check(arrays_.vertex, "vertex");
  check(arrays_.normal, "normal");
  check(arrays_.color, "color");
  check(arrays_.texcoord, "texture coordinate");
  check(arrays_.edge_flag, "edge flag");
}

void Context::array_element_impl(int i) {
  // §2.8: ArrayElement is the sequence of EdgeFlag, Normal, Color, TexCoord and (last) Vertex calls.
  if (arrays_.edge_flag.enabled) glEdgeFlag(array_value_at(arrays_.edge_flag, i, false).x != 0.0);
  if (arrays_.normal.enabled) {
    Vec4 n = array_value_at(arrays_.normal, i, true);
    glNormal3d(n.x, n.y, n.z);
  }
  if (arrays_.color.enabled) {
    Vec4 c = array_value_at(arrays_.color, i, true);
    glColor4d(c.r, c.g, c.b, c.a);
  }
  if (arrays_.texcoord.enabled) {
    Vec4 t = array_value_at(arrays_.texcoord, i, false);
    glTexCoord4d(t.x, t.y, t.z, t.w);
  }
  if (arrays_.vertex.enabled) {
    Vec4 v = array_value_at(arrays_.vertex, i, false);
    glVertex4d(v.x, v.y, v.z, v.w);
  }
}

void Context::compile_array_element(int i, std::vector<Call>& out) const {
  auto add = [&](const char* name, Vec4 v, int n) {
    Call call{find_call(name), {}};
    call.args.reserve(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      Value x;
      x.d = v[k];
      call.args.push_back(x);
    }
    out.push_back(std::move(call));
  };
  check_array_bounds(i);
  if (arrays_.edge_flag.enabled) {
    Call call{find_call("glEdgeFlag"), {Value{}}};
    call.args[0].i = array_value_at(arrays_.edge_flag, i, false).x != 0.0;
    out.push_back(std::move(call));
  }
  if (arrays_.normal.enabled) add("glNormal3d", array_value_at(arrays_.normal, i, true), 3);
  if (arrays_.color.enabled) add("glColor4d", array_value_at(arrays_.color, i, true), 4);
  if (arrays_.texcoord.enabled) add("glTexCoord4d", array_value_at(arrays_.texcoord, i, false), 4);
  if (arrays_.vertex.enabled) add("glVertex4d", array_value_at(arrays_.vertex, i, false), 4);
}

void Context::record_client_arrays(int max_index) {
  // Emits glXxxPointer calls carrying the elements 0..max_index, tightly packed.
  check_array_bounds(max_index);
  auto emit = [&](const ClientArray& a, const char* name) {
    if (!a.enabled || !a.pointer) return;
    const int ts = type_size(a.type);
    const std::size_t elem = static_cast<std::size_t>(ts * a.size);
    const std::size_t stride = a.stride ? static_cast<std::size_t>(a.stride) : elem;
    std::vector<std::byte> packed(elem * static_cast<std::size_t>(max_index + 1));
    for (int k = 0; k <= max_index; ++k)
      std::memcpy(packed.data() + elem * k, static_cast<const std::byte*>(a.pointer) + stride * k, elem);
    // The arguments its row names: size and type (when it has them), stride 0, the data.
    Call call{find_call(name), {}};
    for (const CallInfo::Param& p : call.info->params) {
      Value v;
      if (p.name == "size") v.i = a.size;
      else if (p.name == "type") v.i = a.type;
      else if (p.name == "pointer")
        v = detail::array_value(packed.data(), a.type, static_cast<std::size_t>(a.size) * (max_index + 1));
      call.args.push_back(v);
    }
    sink_->on_call(call);
  };
  emit(arrays_.vertex, "glVertexPointer");
  emit(arrays_.normal, "glNormalPointer");
  emit(arrays_.color, "glColorPointer");
  emit(arrays_.texcoord, "glTexCoordPointer");
  emit(arrays_.edge_flag, "glEdgeFlagPointer");
}

void Context::glArrayElement(GLint i) {
  PASSIM_ENTRY(i)
  if (i < 0) return;
  check_array_bounds(i);
  array_element_impl(i);
}

namespace {
// Marks a glDrawArrays / glDrawElements for its duration, also when a trace error leaves it.
struct ArraysScope {
  bool& flag;
  explicit ArraysScope(bool& f) : flag(f) { flag = true; }
  ~ArraysScope() { flag = false; }
  ArraysScope(const ArraysScope&) = delete;
  ArraysScope& operator=(const ArraysScope&) = delete;
};
}  // namespace

void Context::glDrawArrays(GLenum mode, GLint first, GLsizei count) {
  PASSIM_ENTRY(mode, first, count)
  if (!is_primitive_mode(mode)) return set_error(GL_INVALID_ENUM);
  if (count < 0 || first < 0) return set_error(GL_INVALID_VALUE);
  if (count == 0) return;
  check_array_bounds(std::int64_t{first} + count - 1);
  const ArraysScope arrays(drawing_arrays_);
  glBegin(mode);
  for (GLint k = 0; k < count; ++k) array_element_impl(first + k);
  glEnd();
}

void Context::glDrawElements(GLenum mode, GLsizei count, GLenum type, const void* indices) {
  PASSIM_ENTRY(mode, count, type, indices)
  if (!is_primitive_mode(mode)) return set_error(GL_INVALID_ENUM);
  if (type != GL_UNSIGNED_BYTE && type != GL_UNSIGNED_SHORT && type != GL_UNSIGNED_INT)
    return set_error(GL_INVALID_ENUM);
  if (count < 0) return set_error(GL_INVALID_VALUE);
  if (count == 0 || !indices) return;
  std::vector<int> idx(static_cast<std::size_t>(count));
  std::int64_t max_index = 0;
  for (GLsizei k = 0; k < count; ++k) {
    std::uint32_t v;
    if (type == GL_UNSIGNED_BYTE) v = static_cast<const std::uint8_t*>(indices)[k];
    else if (type == GL_UNSIGNED_SHORT) v = static_cast<const std::uint16_t*>(indices)[k];
    else v = static_cast<const std::uint32_t*>(indices)[k];
    idx[static_cast<std::size_t>(k)] = static_cast<int>(v);  // ≤ INT_MAX once the bounds are checked
    max_index = std::max<std::int64_t>(max_index, v);
  }
  check_array_bounds(max_index);
  const ArraysScope arrays(drawing_arrays_);
  glBegin(mode);
  for (int i : idx) array_element_impl(i);
  glEnd();
}

void Context::glDrawRangeElements(GLenum mode, GLuint start, GLuint end, GLsizei count, GLenum type,
                                  const void* indices) {
  PASSIM_ENTRY(mode, start, end, count, type, indices)
  // §2.8: DrawElements with the promise that every index lies in [start, end] (an index outside
  // is undefined; it is drawn as DrawElements draws it).
  if (end < start) return set_error(GL_INVALID_VALUE);
  glDrawElements(mode, count, type, indices);
}

std::vector<GLenum> Context::adopt_client_array_data(const void* data, std::size_t bytes) {
  // A pointer call the GL rejected (§2.5: the command has no effect) left its arrays as they
  // were, still reading their earlier data: that data stays the caller's to keep.
  std::vector<GLenum> adopted;
  const auto first = reinterpret_cast<std::uintptr_t>(data), last = first + bytes;
  for (GLenum name : {GL_VERTEX_ARRAY, GL_NORMAL_ARRAY, GL_COLOR_ARRAY, GL_TEXTURE_COORD_ARRAY, GL_EDGE_FLAG_ARRAY}) {
    ClientArray& a = *array_of(arrays_, name);
    const auto p = reinterpret_cast<std::uintptr_t>(a.pointer);
    if (a.extent != SIZE_MAX || p < first || p > last || (data == nullptr) != (a.pointer == nullptr)) continue;
    a.extent = last - p;
    adopted.push_back(name);
  }
  return adopted;
}

}  // namespace passim
