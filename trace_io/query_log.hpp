// What the queries of a replay returned (passim run --queries): every call that returns a
// value or writes an output argument, in order, with where it was, its text and its results.
// Arrays of more than kInlineElements values are logged as their size and FNV-1a hash, and
// written to a folder of their own when one is given (--queries-arrays).
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/calls.hpp"

namespace passim {

class QueryLog {
 public:
  static constexpr std::uint64_t kInlineElements = 64;
  // `arrays_dir`: where the large arrays go (created when the first one comes); none: hashes only.
  explicit QueryLog(std::optional<std::filesystem::path> arrays_dir = std::nullopt)
      : arrays_dir_(std::move(arrays_dir)) {}
  QueryLog(const QueryLog&) = delete;
  QueryLog& operator=(const QueryLog&) = delete;
  // Removes the arrays written so far unless commit() kept them (a failed run leaves none).
  ~QueryLog();

  // A call's results; `error`: the GL error the call raised (0: none; its outputs are then
  // left out, as the GL wrote nothing).
  void add(const std::string& where, const CallInfo& info, const std::vector<Value>& args, const CallResults& results,
           GLenum error);
  // {"queries": [...]}, the log so far.
  nlohmann::json json() const;
  std::size_t size() const { return entries_.size(); }
  // The run succeeded: the arrays written stay (they are written to a temporary name first).
  void commit();

 private:
  nlohmann::json output_json(const std::string& call, const CallOutput& out, const std::string& param);

  std::optional<std::filesystem::path> arrays_dir_;
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // temporary, final
  nlohmann::json entries_ = nlohmann::json::array();
};

}  // namespace passim
