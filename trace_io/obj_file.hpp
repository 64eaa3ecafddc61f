// Wavefront OBJ meshes (through tinyobjloader), for @mesh in traces and OBJ scenes: polygons
// triangulated, every vertex and normal index checked, coordinates finite. The file and its
// material library are read as side files (side_files.hpp), so an OBJ cannot reach a file
// outside its folder.
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "trace_io/side_files.hpp"

namespace passim {

// A malformed OBJ file; the message names the file.
struct ObjError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct ObjCorner {
  std::array<float, 3> position{};
  std::optional<std::array<float, 3>> normal;  // when the face gives one
};

struct ObjShape {
  std::string name;
  std::optional<std::array<float, 3>> diffuse;  // its first face's material's Kd
  std::vector<ObjCorner> corners;                // three a triangle, in the file's order
};

// The triangles of OBJ file `name` (a side file of `files`), at most `max_bytes` of text.
std::vector<ObjShape> read_obj(const SideFiles& files, const std::string& name, std::uint64_t max_bytes);

}  // namespace passim
