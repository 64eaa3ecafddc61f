#include "pipeline/counters.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace passim {

Counters& Counters::operator+=(const Counters& o) {
  for_each_field([&](const char*, std::uint64_t Counters::*m) { this->*m += o.*m; });
  return *this;
}

bool Counters::operator==(const Counters& o) const {
  bool same = true;
  for_each_field([&](const char*, std::uint64_t Counters::*m) { same = same && (this->*m == o.*m); });
  return same;
}

std::string Counters::balance_error() const {
  if (fragments_generated == fragments_written + fragments_killed()) return {};
  return fmt::format("fragment balance broken: generated {} != written {} + killed {} (scissor {}, alpha {}, "
                     "stencil {}, depth {})",
                     fragments_generated, fragments_written, fragments_killed(), killed_scissor, killed_alpha,
                     killed_stencil, killed_depth);
}

nlohmann::json Counters::to_json() const {
  nlohmann::json j = nlohmann::json::object();
  for_each_field([&](const char* name, std::uint64_t Counters::*m) { j[name] = this->*m; });
  return j;
}

}  // namespace passim
