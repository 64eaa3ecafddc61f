// The files a trace reads besides itself — file("...") arrays, @mesh OBJ files and their
// material libraries — read under the rules for input from strangers (docs/hostile-input.md):
// a regular file inside the trace's own folder, named by a relative path without "..", no
// device, FIFO, socket or directory, no link that leads out of the folder, and no more bytes
// than the caller allows. Folders given with --allow-files widen the folder rule: a name may
// then be absolute or climb with "..", as long as it resolves inside one of them.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace passim {

// A side file that may not be read; the message names the file and the rule.
struct SideFileRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class SideFiles {
 public:
  // `folder`: the trace's folder ("" = the current one); `allowed`: further folders.
  explicit SideFiles(std::filesystem::path folder, std::vector<std::filesystem::path> allowed = {});

  // The file `name` names, once every rule holds (it exists and is a regular file).
  std::filesystem::path resolve(const std::string& name) const;
  // The same, but nothing when no such file exists (the rules on the name still throw).
  std::optional<std::filesystem::path> find(const std::string& name) const;
  // Its bytes; SideFileRefused beyond `max_bytes`.
  std::string read(const std::string& name, std::uint64_t max_bytes) const;

  const std::filesystem::path& folder() const { return folder_; }

 private:
  std::filesystem::path folder_;
  std::vector<std::filesystem::path> allowed_;
};

}  // namespace passim
