// A run's memory budget (--max-memory; docs/hostile-input.md). What the GL allocates for
// the application — planes, texture images, colour tables, filters, histograms, pixel maps,
// display lists, names — and what a replay holds for it (client arrays, side files) is
// charged here before it is allocated. A GL allocation past the budget raises
// GL_OUT_OF_MEMORY (§2.5) and has no effect; anything else past it ends the run with a message.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>

namespace passim {

inline constexpr std::uint64_t kDefaultMemoryBudget = std::uint64_t{1} << 30;  // 1 GiB

// A run asked for more memory than its budget allows (not a GL allocation).
struct BudgetExceeded : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MemoryBudget {
 public:
  explicit MemoryBudget(std::uint64_t limit = kDefaultMemoryBudget) : limit_(limit) {}
  std::uint64_t limit() const { return limit_; }
  std::uint64_t used() const { return used_; }
  std::uint64_t peak() const { return peak_; }
  std::uint64_t left() const { return limit_ - used_; }
  // Charges `bytes` if they fit; false (and nothing charged) if not.
  bool try_charge(std::uint64_t bytes) {
    if (bytes > left()) return false;
    used_ += bytes;
    if (used_ > peak_) peak_ = used_;
    return true;
  }
  // try_charge, or BudgetExceeded naming `what`.
  void charge(std::uint64_t bytes, const std::string& what);
  void release(std::uint64_t bytes) { used_ -= bytes < used_ ? bytes : used_; }

 private:
  std::uint64_t limit_;
  std::uint64_t used_ = 0, peak_ = 0;
};

}  // namespace passim
