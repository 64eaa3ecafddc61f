#include "trace_io/obj_file.hpp"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
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

// Every index of every face corner (v, v/vt, v//vn, v/vt/vn), checked on the text before
// tinyobjloader reads it: its atoi wraps an index beyond int (99999999999999999999 becomes -1,
// the last vertex), and a relative index one before the first becomes -1, its "no normal" or
// "no texture coordinate", so a file naming elements it does not define would draw silently.
// A positive index may name any element of the file; a negative one counts back from the
// elements defined before its line (the OBJ format's relative indices).
void check_face_indices(const std::string& text, const std::string& name) {
  const char* const what[3] = {"vertex", "texture coordinate", "normal"};
  auto kind_of = [](const std::string& keyword) { return keyword == "v" ? 0 : keyword == "vt" ? 1 : keyword == "vn" ? 2 : -1; };
  std::int64_t total[3] = {0, 0, 0}, so_far[3] = {0, 0, 0};
  {
    std::istringstream in(text);
    std::string line, keyword;
    while (std::getline(in, line))
      if (std::istringstream(line) >> keyword && kind_of(keyword) >= 0) ++total[kind_of(keyword)];
  }
  std::istringstream in(text);
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    std::istringstream words(line);
    std::string keyword, corner;
    if (!(words >> keyword)) continue;
    if (kind_of(keyword) >= 0) ++so_far[kind_of(keyword)];
    if (keyword != "f") continue;
    while (words >> corner) {
      std::size_t start = 0;
      for (int k = 0; k < 3; ++k) {
        const std::size_t slash = std::min(corner.find('/', start), corner.size());
        const std::string index = corner.substr(start, slash - start);
        if (!index.empty() || k == 0) {
          std::int64_t i = 0;
          const char* first = index.data();
          const char* last = first + index.size();
          const auto [end, ec] = std::from_chars(first, last, i);
          const bool number = end == last && !index.empty() && (ec == std::errc() || ec == std::errc::result_out_of_range);
          if (!number)
            throw ObjError(fmt::format("{}:{}: a face corner '{}' is not an index", name, line_no, corner));
          const bool defined = ec == std::errc() && ((i > 0 && i <= total[k]) || (i < 0 && -i <= so_far[k]));
          if (!defined)
            throw ObjError(fmt::format("{}:{}: a face refers to {} {}, which the file does not define ({} in the file, "
                                       "{} before this line)",
                                       name, line_no, what[k], index, total[k], so_far[k]));
        }
        if (slash == corner.size()) break;
        start = slash + 1;
      }
    }
  }
}

}  // namespace

std::vector<ObjShape> read_obj(const SideFiles& files, const std::string& name, std::uint64_t max_bytes) {
  const std::string text = files.read(name, max_bytes);
  std::string materials;
  if (const auto library = material_library(text)) {
    // A library that is missing leaves the default colours (as tinyobjloader does); one the
    // side-file rules refuse is an error.
    // Found through the side-file rules first, so a library outside the folder is refused
    // before anything is asked of the file system about it.
    const std::filesystem::path relative = std::filesystem::path(name).parent_path() / *library;
    if (files.find(relative.string())) materials = files.read(relative.string(), max_bytes);
  }
  check_face_indices(text, name);
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
