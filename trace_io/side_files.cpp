#include "trace_io/side_files.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <system_error>

namespace passim {
namespace fs = std::filesystem;

namespace {

// Whether `path` is `folder` or below it (both canonical).
bool inside(const fs::path& path, const fs::path& folder) {
  auto p = path.begin(), f = folder.begin();
  for (; f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

// The name as a message may show it: a NUL would end the message there (what() is a C
// string) and a control character could rewrite the terminal, so both are written \xHH.
std::string printable(const std::string& name) {
  std::string out;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) out += fmt::format("\\x{:02x}", u);
    else out += c;
  }
  return out;
}

fs::path canonical_folder(const fs::path& folder) {
  std::error_code ec;
  fs::path c = fs::canonical(folder.empty() ? fs::path(".") : folder, ec);
  return ec ? fs::absolute(folder.empty() ? fs::path(".") : folder).lexically_normal() : c;
}

}  // namespace

SideFiles::SideFiles(fs::path folder, std::vector<fs::path> allowed) : folder_(canonical_folder(folder)) {
  for (const fs::path& a : allowed) allowed_.push_back(canonical_folder(a));
}

fs::path SideFiles::resolve(const std::string& name) const {
  const std::optional<fs::path> found = find(name);
  if (!found)
    throw SideFileRefused(fmt::format("cannot read side file '{}' ({})", printable(name),
                                      std::make_error_code(std::errc::no_such_file_or_directory).message()));
  return *found;
}

std::optional<fs::path> SideFiles::find(const std::string& name) const {
  auto refuse = [&](const std::string& why) -> fs::path {
    throw SideFileRefused(fmt::format("side file '{}' refused: {}", printable(name), why));
  };
  if (name.empty()) return refuse("the name is empty");
  if (name.find('\0') != std::string::npos) return refuse("the name holds a NUL character");
  const fs::path given(name);
  const bool widened = !allowed_.empty();
  if (!widened && given.is_absolute())
    return refuse("an absolute path; side files are named relative to the trace's folder (--allow-files DIR "
                  "widens this)");
  if (!widened && std::any_of(given.begin(), given.end(), [](const fs::path& part) { return part == ".."; }))
    return refuse("'..' leaves the trace's folder (--allow-files DIR widens this)");
  const fs::path joined = given.is_absolute() ? given : folder_ / given;
  std::error_code ec;
  const fs::path real = fs::canonical(joined, ec);  // follows every link
  // Missing (the name passed the rules above, so this says nothing of other folders).
  if (ec == std::errc::no_such_file_or_directory) return std::nullopt;
  if (ec) throw SideFileRefused(fmt::format("cannot read side file '{}' ({})", printable(name), ec.message()));
  bool ok = inside(real, folder_);
  for (const fs::path& a : allowed_) ok = ok || inside(real, a);
  if (!ok)
    return refuse(widened ? "it resolves outside the trace's folder and the --allow-files folders"
                          : "a link leads out of the trace's folder (--allow-files DIR widens this)");
  const fs::file_status status = fs::status(real, ec);
  if (ec) return refuse(fmt::format("cannot be read ({})", ec.message()));
  if (!fs::is_regular_file(status)) return refuse("not a regular file (a directory, device, FIFO or socket)");
  return real;
}

std::string SideFiles::read(const std::string& name, std::uint64_t max_bytes) const {
  const fs::path path = resolve(name);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw SideFileRefused(fmt::format("side file '{}' cannot be read ({})", printable(name), ec.message()));
  if (size > max_bytes)
    throw SideFileRefused(fmt::format("side file '{}' holds {} bytes, more than the {} the run's memory budget "
                                      "leaves (--max-memory)",
                                      printable(name), size, max_bytes));
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (!in || !in.read(bytes.data(), static_cast<std::streamsize>(size)) || in.gcount() != static_cast<std::streamsize>(size))
    throw SideFileRefused(fmt::format("side file '{}' cannot be read whole", printable(name)));
  return bytes;
}

}  // namespace passim
