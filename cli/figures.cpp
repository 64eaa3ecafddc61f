#include "cli/figures.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "cli/process.hpp"

namespace fs = std::filesystem;

namespace passim {
namespace {

#ifndef PASSIM_PYTHON3
#define PASSIM_PYTHON3 ""
#endif
#ifndef PASSIM_INSTALLED_PYTHON_DIR
#define PASSIM_INSTALLED_PYTHON_DIR ""
#endif

// The folder holding the package passim/ (with figures.py): beside this executable
// (build/passim -> build/python), or the install's; "" to leave it to python3's own path.
std::string package_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::vector<fs::path> candidates;
  if (!ec) candidates.push_back(exe.parent_path() / "python");
  candidates.push_back(PASSIM_INSTALLED_PYTHON_DIR);
  for (const fs::path& dir : candidates)
    if (!dir.empty() && fs::exists(dir / "passim" / "figures.py", ec)) return dir.string();
  return "";
}

std::string interpreter() {
  if (const char* own = std::getenv("PASSIM_PYTHON3"); own && *own) return own;
  const std::string built = PASSIM_PYTHON3;
  if (!built.empty() && access(built.c_str(), X_OK) == 0) return built;
  return "python3";
}

}  // namespace

FigureRun draw_figures(const std::vector<std::string>& args) {
  FigureRun f;
  const std::string python = interpreter();
  std::vector<std::string> argv{python, "-m", "passim.figures"};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<std::string> env;
  const std::string dir = package_dir();
  if (!dir.empty()) {
    const char* old = std::getenv("PYTHONPATH");
    env.push_back(old && *old ? fmt::format("PYTHONPATH={}:{}", dir, old) : fmt::format("PYTHONPATH={}", dir));
  }
  env.push_back("MPLBACKEND=Agg");
  const ProcessResult r = run_process(argv, env);
  if (!r.started) {
    f.message = fmt::format("{} not found (Debian: apt-get install python3 python3-matplotlib)", python);
    return f;
  }
  if (r.status != 0) {
    std::string err = r.err;
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    if (err.find("No module named passim") != std::string::npos || err.find("No module named 'passim'") != std::string::npos)
      f.message = fmt::format("passim's Python package not found beside the executable or in {} (build with "
                              "-DPASSIM_PYTHON=ON, or cmake --install)", PASSIM_INSTALLED_PYTHON_DIR);
    else
      f.message = err.empty() ? fmt::format("{} -m passim.figures exited with status {}", python, r.status) : err;
    return f;
  }
  std::stringstream lines(r.out);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) f.files.push_back(line);
  f.ok = true;
  return f;
}

}  // namespace passim
