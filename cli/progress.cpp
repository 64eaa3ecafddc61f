#include "cli/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace passim {
namespace {

// Below this nothing is shown: work that ends within a second needs no progress line.
constexpr double kQuietStart = 1.0;
// A plain line (stderr not a terminal) at most this often, so that a log stays readable.
constexpr double kPlainInterval = 5.0;
// A terminal's line at most this often.
constexpr double kTerminalInterval = 0.2;

}  // namespace

Progress::Progress(std::string what, int total, bool quiet, std::string unit)
    : what_(std::move(what)), unit_(std::move(unit)), total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

Progress::~Progress() { finish(); }

double Progress::seconds_left(double elapsed, int done, int total) {
  if (done <= 0 || total <= done) return 0.0;
  return elapsed / done * (total - done);
}

std::string Progress::duration(double s) {
  const long total = std::lround(s);
  if (total < 60) return fmt::format("{} s", total);
  if (total < 3600) return fmt::format("{} min {:02} s", total / 60, total % 60);
  return fmt::format("{} h {:02} min", total / 3600, (total % 3600) / 60);
}

void Progress::step(int done, const std::string& detail) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since = std::chrono::duration<double>(now - last_).count();
  const bool last = done >= total_;
  if (elapsed < kQuietStart) return;
  if (!last && shown_ && since < (tty_ ? kTerminalInterval : kPlainInterval)) return;
  std::string line = unit_ == "%" ? fmt::format("{}: {} % done, {}", what_, done, duration(elapsed))
                                  : fmt::format("{}: {}/{} {}, {}", what_, done, total_, unit_, duration(elapsed));
  if (!last && done > 0) line += fmt::format(", about {} left", duration(seconds_left(elapsed, done, total_)));
  if (!detail.empty()) line += fmt::format(" ({})", detail);
  if (tty_)
    std::fprintf(stderr, "\r\033[K%s", line.c_str());  // rewrite the line in place
  else
    std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
  shown_ = true;
  last_ = now;
}

void Progress::finish() {
  if (tty_ && shown_) std::fputs("\n", stderr);
  shown_ = false;
}

}  // namespace passim
