// GL types and enum values, taken from Debian's <GL/gl.h> and <GL/glext.h>
// (libgl-dev), so every value is the one real GL programs use.
#pragma once
#include <GL/gl.h>
#include <GL/glext.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace passim {

// Hint for printing an enum whose value has several names (0 is GL_ZERO,
// GL_NONE, GL_POINTS, GL_FALSE ...): the parameter's role decides.
enum class EnumRole : std::uint8_t { Generic, PrimitiveMode, Buffer, Boolean };

// Value of "GL_NAME" (names from gl.h and glext.h); nullopt when unknown.
std::optional<std::uint32_t> enum_value(std::string_view name);
// The canonical name of a value for a role; "0x...." when it has none.
std::string enum_name(std::uint32_t value, EnumRole role = EnumRole::Generic);
// The names of bits set in a GL bitfield ("GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT").
std::string bitfield_name(std::uint32_t value);

}  // namespace passim
