#include "trace_io/query_log.hpp"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "pipeline/gl.hpp"
#include "trace_io/trace.hpp"

namespace passim {

namespace {
// Element k of an output written as `type`.
nlohmann::json element(const CallOutput& out, std::uint64_t k) {
  auto read = [&](auto sample) {
    decltype(sample) v;
    std::memcpy(&v, out.bytes.data() + k * sizeof v, sizeof v);
    return v;
  };
  switch (out.type) {
    case GL_FLOAT: return static_cast<double>(read(GLfloat{}));
    case GL_DOUBLE: return read(GLdouble{});
    case GL_INT: return read(GLint{});
    case GL_UNSIGNED_INT: return read(GLuint{});
    case GL_SHORT: return read(GLshort{});
    case GL_UNSIGNED_SHORT: return read(GLushort{});
    case GL_BYTE: return read(GLbyte{});
    default: return read(GLubyte{});  // UNSIGNED_BYTE, GLboolean, BITMAP
  }
}

std::uint64_t element_bytes(GLenum type) {
  const int size = type_size(type);
  return size > 0 ? static_cast<std::uint64_t>(size) : 1;
}
}  // namespace

QueryLog::~QueryLog() {
  std::error_code ignored;
  for (const auto& [temporary, final_path] : staged_) std::filesystem::remove(temporary, ignored);
}

nlohmann::json QueryLog::output_json(const std::string& call, const CallOutput& out, const std::string& param) {
  const std::uint64_t bytes = out.elements * element_bytes(out.type);
  if (out.elements <= kInlineElements) {
    nlohmann::json values = nlohmann::json::array();
    for (std::uint64_t k = 0; k < out.elements; ++k) values.push_back(element(out, k));
    return values;
  }
  nlohmann::json j = {{"elements", out.elements},
                      {"type", enum_name(out.type)},
                      {"fnv1a", fmt::format("{:016x}", fnv1a({out.bytes.data(), bytes}))}};
  if (arrays_dir_) {
    // NNNNNN-call-param.bin: the bytes as the GL wrote them (the element type's, little-endian).
    const std::string name = fmt::format("{:06}-{}-{}.bin", entries_.size(), call, param);
    std::filesystem::create_directories(*arrays_dir_);
    const std::filesystem::path final_path = *arrays_dir_ / name, temporary = *arrays_dir_ / ("." + name + ".part");
    staged_.emplace_back(temporary, final_path);
    std::ofstream file(temporary, std::ios::binary);
    file.write(reinterpret_cast<const char*>(out.bytes.data()), static_cast<std::streamsize>(bytes));
    if (!file.flush()) throw std::runtime_error(fmt::format("cannot write {}", temporary.string()));
    j["file"] = name;
  }
  return j;
}

void QueryLog::add(const std::string& where, const CallInfo& info, const std::vector<Value>& args,
                   const CallResults& results, GLenum error) {
  nlohmann::json entry = {{"at", where}, {"call", format_call(Call{&info, args})}};
  if (results.returned) {
    if (results.value.text) entry["returned"] = results.value.str();
    else entry["returned"] = results.value.i;
  }
  if (error) {
    entry["error"] = enum_name(error);
  } else if (!results.outputs.empty()) {
    nlohmann::json outputs = nlohmann::json::object();
    for (const CallOutput& out : results.outputs) {
      const std::string param(info.params[out.param].name);
      outputs[param] = output_json(std::string(info.name), out, param);
    }
    entry["outputs"] = std::move(outputs);
  }
  entries_.push_back(std::move(entry));
}

nlohmann::json QueryLog::json() const { return {{"queries", entries_}}; }

void QueryLog::commit() {
  for (const auto& [temporary, final_path] : staged_) std::filesystem::rename(temporary, final_path);
  staged_.clear();
}

}  // namespace passim
