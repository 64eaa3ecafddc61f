// Parsing of the command line's compound values, one way everywhere: WIDTHxHEIGHT, NxN
// footprints, comma-separated lists. Each throws std::invalid_argument naming the option.
#pragma once
#include <fmt/format.h>

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace passim {

// "800x600" -> width, height (each at least 1).
inline void parse_size(const std::string& text, int& width, int& height, const char* option = "--size") {
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1)
    throw std::invalid_argument(fmt::format("{} {}: expected WIDTHxHEIGHT, e.g. 800x600", option, text));
  width = w, height = h;
}

// "2x2" or "2" -> 2; a footprint is square.
inline int parse_filter(const std::string& text, const char* option = "--filter") {
  int a = 0, b = 0;
  char tail = 0;
  const int got = std::sscanf(text.c_str(), "%dx%d%c", &a, &b, &tail);
  if (got < 1 || got > 2 || (got == 2 && a != b))
    throw std::invalid_argument(fmt::format("{} {}: expected NxN (square), e.g. 2x2", option, text));
  return a;
}

// "a,b,,c" -> {a, b, c}.
inline std::vector<std::string> parse_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace passim
