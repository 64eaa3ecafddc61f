#include "trace_io/obj_file.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <cmath>
#include <filesystem>
#include <sstream>

namespace passim {

namespace {

// The material library an OBJ names ("mtllib NAME"), if any.
std::optional<std::string> material_library(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string keyword, name;
    if (words >> keyword >> name && keyword == "mtllib") return name;
  }
  return std::nullopt;
}

}  // namespace

std::vector<ObjShape> read_obj(const SideFiles& files, const std::string& name, std::uint64_t max_bytes) {
  const std::string text = files.read(name, max_bytes);
  std::string materials;
  if (const auto library = material_library(text)) {
    // A library that is missing leaves the default colours (as tinyobjloader does); one the
    // side-file rules refuse is an error.
    std::error_code ec;
    const std::filesystem::path relative = std::filesystem::path(name).parent_path() / *library;
    if (std::filesystem::exists(files.folder() / relative, ec)) materials = files.read(relative.string(), max_bytes);
  }
  tinyobj::ObjReader reader;
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  if (!reader.ParseFromString(text, materials, config)) {
    std::string why = reader.Error();
    while (!why.empty() && why.back() == '\n') why.pop_back();
    throw ObjError(fmt::format("{}: cannot read the OBJ file: {}", name, why.empty() ? "no reason given" : why));
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  auto triple = [&](const std::vector<tinyobj::real_t>& values, int index, const char* what) {
    const std::size_t at = 3 * static_cast<std::size_t>(index);
    if (index < 0 || at + 2 >= values.size())
      throw ObjError(fmt::format("{}: a face refers to {} {}, which the file does not define", name, what, index + 1));
    std::array<float, 3> v{values[at], values[at + 1], values[at + 2]};
    for (float c : v)
      if (!std::isfinite(c)) throw ObjError(fmt::format("{}: {} {} is not a finite number", name, what, index + 1));
    return v;
  };
  std::vector<ObjShape> shapes;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    ObjShape out;
    out.name = shape.name;
    const auto& ids = shape.mesh.material_ids;
    if (!ids.empty() && ids[0] >= 0 && static_cast<std::size_t>(ids[0]) < reader.GetMaterials().size()) {
      const tinyobj::material_t& m = reader.GetMaterials()[static_cast<std::size_t>(ids[0])];
      out.diffuse = std::array<float, 3>{m.diffuse[0], m.diffuse[1], m.diffuse[2]};
    }
    const std::size_t whole = shape.mesh.indices.size() / 3 * 3;  // triangulated: three a face
    for (std::size_t k = 0; k < whole; ++k) {
      const tinyobj::index_t& i = shape.mesh.indices[k];
      ObjCorner c;
      c.position = triple(attrib.vertices, i.vertex_index, "vertex");
      if (i.normal_index >= 0) c.normal = triple(attrib.normals, i.normal_index, "normal");
      out.corners.push_back(c);
    }
    shapes.push_back(std::move(out));
  }
  return shapes;
}

}  // namespace passim
