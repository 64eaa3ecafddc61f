// Enum name table (generated at build time from <GL/gl.h>, <GL/glext.h>).
#include "pipeline/gl.hpp"

#include <fmt/format.h>

#include <array>
#include <unordered_map>
#include <utility>

namespace passim {
namespace {

struct EnumRow {
  const char* name;
  std::uint32_t value;
  int from_gl_h;
};

constexpr EnumRow kRows[] = {
#include "gl_enum_table.inc"
};

struct Tables {
  std::unordered_map<std::string_view, std::uint32_t> by_name;
  std::unordered_map<std::uint32_t, const EnumRow*> by_value;
  // Prefer gl.h names, then names without a vendor suffix, then the first seen.
  static int rank(const EnumRow& row) {
    std::string_view n = row.name;
    int r = row.from_gl_h ? 0 : 2;
    for (std::string_view suffix : {"_EXT", "_ARB", "_SGI", "_SGIX", "_SGIS", "_NV", "_ATI", "_APPLE", "_MESA",
                                    "_OES", "_KHR", "_HP", "_IBM", "_INTEL", "_AMD"}) {
      if (n.size() > suffix.size() && n.substr(n.size() - suffix.size()) == suffix) return r + 1;
    }
    return r;
  }
  Tables() {
    for (const EnumRow& row : kRows) {
      by_name.emplace(row.name, row.value);
      auto [it, inserted] = by_value.emplace(row.value, &row);
      if (!inserted && rank(row) < rank(*it->second)) it->second = &row;
    }
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

}  // namespace

std::optional<std::uint32_t> enum_value(std::string_view name) {
  const auto& t = tables();
  auto it = t.by_name.find(name);
  if (it == t.by_name.end()) return std::nullopt;
  return it->second;
}

std::string enum_name(std::uint32_t value, EnumRole role) {
  // Values shared by several unrelated names: the role of the parameter picks one.
  if (value <= 9 && role == EnumRole::PrimitiveMode) {
    static constexpr std::array<const char*, 10> modes = {
        "GL_POINTS",    "GL_LINES", "GL_LINE_LOOP", "GL_LINE_STRIP", "GL_TRIANGLES", "GL_TRIANGLE_STRIP",
        "GL_TRIANGLE_FAN", "GL_QUADS", "GL_QUAD_STRIP", "GL_POLYGON"};
    return modes[value];
  }
  if (role == EnumRole::Boolean && value <= 1) return value ? "GL_TRUE" : "GL_FALSE";
  if (value == 0) return role == EnumRole::Buffer ? "GL_NONE" : "GL_ZERO";
  if (value == 1) return "GL_ONE";
  const auto& t = tables();
  auto it = t.by_value.find(value);
  if (it == t.by_value.end()) return fmt::format("0x{:04X}", value);
  return std::string(it->second->name);
}

std::string bitfield_name(std::uint32_t value) {
  static constexpr std::pair<std::uint32_t, const char*> bits[] = {
      {GL_CURRENT_BIT, "GL_CURRENT_BIT"},
      {GL_POINT_BIT, "GL_POINT_BIT"},
      {GL_LINE_BIT, "GL_LINE_BIT"},
      {GL_POLYGON_BIT, "GL_POLYGON_BIT"},
      {GL_POLYGON_STIPPLE_BIT, "GL_POLYGON_STIPPLE_BIT"},
      {GL_PIXEL_MODE_BIT, "GL_PIXEL_MODE_BIT"},
      {GL_LIGHTING_BIT, "GL_LIGHTING_BIT"},
      {GL_FOG_BIT, "GL_FOG_BIT"},
      {GL_DEPTH_BUFFER_BIT, "GL_DEPTH_BUFFER_BIT"},
      {GL_ACCUM_BUFFER_BIT, "GL_ACCUM_BUFFER_BIT"},
      {GL_STENCIL_BUFFER_BIT, "GL_STENCIL_BUFFER_BIT"},
      {GL_VIEWPORT_BIT, "GL_VIEWPORT_BIT"},
      {GL_TRANSFORM_BIT, "GL_TRANSFORM_BIT"},
      {GL_ENABLE_BIT, "GL_ENABLE_BIT"},
      {GL_COLOR_BUFFER_BIT, "GL_COLOR_BUFFER_BIT"},
      {GL_HINT_BIT, "GL_HINT_BIT"},
      {GL_EVAL_BIT, "GL_EVAL_BIT"},
      {GL_LIST_BIT, "GL_LIST_BIT"},
      {GL_TEXTURE_BIT, "GL_TEXTURE_BIT"},
      {GL_SCISSOR_BIT, "GL_SCISSOR_BIT"},
  };
  if (value == 0) return "0";
  if (value == GL_ALL_ATTRIB_BITS) return "GL_ALL_ATTRIB_BITS";
  std::string out;
  std::uint32_t rest = value;
  for (const auto& [bit, name] : bits) {
    if (value & bit) {
      if (!out.empty()) out += " | ";
      out += name;
      rest &= ~bit;
    }
  }
  if (rest) {
    if (!out.empty()) out += " | ";
    out += fmt::format("0x{:X}", rest);
  }
  return out;
}

std::string client_bitfield_name(std::uint32_t value) {
  if (value == GL_CLIENT_ALL_ATTRIB_BITS) return "GL_CLIENT_ALL_ATTRIB_BITS";
  if (value == 0) return "0";
  std::string out;
  std::uint32_t rest = value;
  for (const auto& [bit, name] : {std::pair<std::uint32_t, const char*>{GL_CLIENT_PIXEL_STORE_BIT, "GL_CLIENT_PIXEL_STORE_BIT"},
                                  {GL_CLIENT_VERTEX_ARRAY_BIT, "GL_CLIENT_VERTEX_ARRAY_BIT"}}) {
    if (value & bit) {
      if (!out.empty()) out += " | ";
      out += name;
      rest &= ~bit;
    }
  }
  if (rest) {
    if (!out.empty()) out += " | ";
    out += fmt::format("0x{:X}", rest);
  }
  return out;
}

}  // namespace passim
