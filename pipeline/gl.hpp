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
// GL_ALL_ATTRIB_BITS for every bit.
std::string bitfield_name(std::uint32_t value);
// The same for PushClientAttrib's bits ("GL_CLIENT_PIXEL_STORE_BIT", GL_CLIENT_ALL_ATTRIB_BITS).
std::string client_bitfield_name(std::uint32_t value);

// An enum passed through a float parameter (glTexParameterf(..., GL_LINEAR)): its value when it
// is a whole number in GLenum's range, else 0, which no such parameter accepts — so a negative,
// fractional, huge or NaN value is GL_INVALID_ENUM rather than an undefined conversion.
inline GLenum enum_param(double v) {
  return v >= 0.0 && v <= 4294967295.0 && v == static_cast<double>(static_cast<std::uint64_t>(v))
             ? static_cast<GLenum>(v)
             : 0;
}
// An integer passed through a float parameter, saturated to GLint's range (NaN: 0).
inline GLint int_param(double v) {
  if (!(v == v)) return 0;
  return v <= -2147483648.0 ? INT32_MIN : v >= 2147483647.0 ? INT32_MAX : static_cast<GLint>(v);
}

}  // namespace passim
