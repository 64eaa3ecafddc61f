// Context: vertex arrays (§2.8).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
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
#undef PASSIM_SET_POINTER

Vec4 Context::array_value_at(const ClientArray& a, int i, bool normalise) const {
  // Reads element i; with `normalise`, integer components map to [0,1] or [-1,1] (Table 2.6).
  const int ts = type_size(a.type);
  const std::size_t stride = a.stride ? static_cast<std::size_t>(a.stride) : static_cast<std::size_t>(ts * a.size);
  const std::byte* p = static_cast<const std::byte*>(a.pointer) + stride * static_cast<std::size_t>(i);
  Vec4 out(0.0, 0.0, 0.0, 1.0);
  for (int k = 0; k < a.size; ++k) {
    const std::byte* e = p + k * ts;
    double v = 0.0;
    switch (a.type) {
      case GL_FLOAT: { float f; std::memcpy(&f, e, 4); v = f; break; }
      case GL_DOUBLE: { std::memcpy(&v, e, 8); break; }
      case GL_INT: { std::int32_t x; std::memcpy(&x, e, 4); v = normalise ? (2.0 * x + 1.0) / 4294967295.0 : x; break; }
      case GL_UNSIGNED_INT: { std::uint32_t x; std::memcpy(&x, e, 4); v = normalise ? x / 4294967295.0 : x; break; }
      case GL_SHORT: { std::int16_t x; std::memcpy(&x, e, 2); v = normalise ? (2.0 * x + 1.0) / 65535.0 : x; break; }
      case GL_UNSIGNED_SHORT: { std::uint16_t x; std::memcpy(&x, e, 2); v = normalise ? x / 65535.0 : x; break; }
      case GL_BYTE: { std::int8_t x; std::memcpy(&x, e, 1); v = normalise ? (2.0 * x + 1.0) / 255.0 : x; break; }
      case GL_UNSIGNED_BYTE: { std::uint8_t x; std::memcpy(&x, e, 1); v = normalise ? x / 255.0 : x; break; }
      default: break;
    }
    out[k] = v;
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
}

void Context::array_element_impl(int i) {
  // §2.8: ArrayElement is the sequence of Normal, Color, TexCoord and (last) Vertex calls.
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
  if (arrays_.normal.enabled) add("glNormal3d", array_value_at(arrays_.normal, i, true), 3);
  if (arrays_.color.enabled) add("glColor4d", array_value_at(arrays_.color, i, true), 4);
  if (arrays_.texcoord.enabled) add("glTexCoord4d", array_value_at(arrays_.texcoord, i, false), 4);
  if (arrays_.vertex.enabled) add("glVertex4d", array_value_at(arrays_.vertex, i, false), 4);
}

void Context::record_client_arrays(int max_index) {
  // Emits glXxxPointer calls carrying the elements 0..max_index, tightly packed.
  check_array_bounds(max_index);
  auto emit = [&](const ClientArray& a, const char* name, bool has_size) {
    if (!a.enabled || !a.pointer) return;
    const int ts = type_size(a.type);
    const std::size_t elem = static_cast<std::size_t>(ts * a.size);
    const std::size_t stride = a.stride ? static_cast<std::size_t>(a.stride) : elem;
    std::vector<std::byte> packed(elem * static_cast<std::size_t>(max_index + 1));
    for (int k = 0; k <= max_index; ++k)
      std::memcpy(packed.data() + elem * k, static_cast<const std::byte*>(a.pointer) + stride * k, elem);
    Call call{find_call(name), {}};
    Value size, type, zero, data;
    size.i = a.size;
    type.i = a.type;
    data = detail::array_value(packed.data(), a.type, static_cast<std::size_t>(a.size) * (max_index + 1));
    if (has_size) call.args.push_back(size);
    call.args.push_back(type);
    call.args.push_back(zero);
    call.args.push_back(data);
    sink_->on_call(call);
  };
  emit(arrays_.vertex, "glVertexPointer", true);
  emit(arrays_.normal, "glNormalPointer", false);
  emit(arrays_.color, "glColorPointer", true);
  emit(arrays_.texcoord, "glTexCoordPointer", true);
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

}  // namespace passim
