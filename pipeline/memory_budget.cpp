#include "pipeline/memory_budget.hpp"

#include <fmt/format.h>

namespace passim {

void MemoryBudget::charge(std::uint64_t bytes, const std::string& what) {
  if (!try_charge(bytes))
    throw BudgetExceeded(fmt::format("{} needs {} bytes, but only {} of the run's {} are left (--max-memory)", what,
                                     bytes, left(), limit_));
}

}  // namespace passim
