#include "trace_io/call_set.hpp"

#include <fmt/format.h>

#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace passim {

namespace {
struct Scanner {
  const std::string& s;
  std::size_t pos = 0;
  void skip() {
    while (pos < s.size() && (std::isspace(static_cast<unsigned char>(s[pos])) || s[pos] == ',')) ++pos;
  }
  bool at(char c) const { return pos < s.size() && s[pos] == c; }
  bool digit() const { return pos < s.size() && std::isdigit(static_cast<unsigned char>(s[pos])); }
  bool alpha() const { return pos < s.size() && std::isalpha(static_cast<unsigned char>(s[pos])); }
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument(fmt::format("call set '{}': {} at character {}", s, what, pos + 1));
  }
  std::uint64_t number() {
    if (!digit()) fail("expected a call number");
    std::uint64_t n = 0;
    while (digit()) {
      const std::uint64_t d = static_cast<std::uint64_t>(s[pos++] - '0');
      if (n > (UINT64_MAX - d) / 10) fail("call number too large");
      n = n * 10 + d;
    }
    return n;
  }
  std::string word() {
    std::string w;
    while (alpha()) w.push_back(s[pos++]);
    return w;
  }
};
}  // namespace

CallSet CallSet::parse(const std::string& text) {
  CallSet set;
  Scanner sc{text};
  auto only = [&](const std::string& w) {
    if (w == "frame") return Only::Frame;
    if (w == "draw" || w == "render") return Only::Draw;
    sc.fail(fmt::format("'{}' is not a call frequency (frame, draw)", w));
  };
  sc.skip();
  if (sc.at('@')) {  // the whole set from a file
    const std::string file = text.substr(sc.pos + 1);
    std::ifstream in(file);
    if (!in) throw std::invalid_argument(fmt::format("call set: cannot read '{}'", file));
    std::stringstream ss;
    ss << in.rdbuf();
    return parse(ss.str());
  }
  while (sc.pos < text.size()) {
    Range r;
    if (sc.alpha()) {
      r.only = only(sc.word());
    } else {
      if (sc.at('*')) {
        ++sc.pos;
      } else {
        r.first = r.last = sc.number();
        if (sc.at('-')) {
          ++sc.pos;
          r.last = sc.digit() ? sc.number() : UINT64_MAX;
          if (r.last < r.first) sc.fail("a range that ends before it starts");
        }
      }
      if (sc.at('/')) {
        ++sc.pos;
        if (sc.digit()) {
          r.step = sc.number();
          if (r.step == 0) sc.fail("a step of 0");
        } else {
          r.only = only(sc.word());
        }
      }
    }
    if (sc.pos < text.size() && !std::isspace(static_cast<unsigned char>(text[sc.pos])) && text[sc.pos] != ',')
      sc.fail(fmt::format("unexpected '{}'", text[sc.pos]));
    set.ranges_.push_back(r);
    sc.skip();
  }
  if (set.ranges_.empty()) throw std::invalid_argument("call set is empty");
  return set;
}

bool CallSet::contains(std::uint64_t call, bool ends_frame, bool draws) const {
  for (const Range& r : ranges_) {
    if (call < r.first || call > r.last || (call - r.first) % r.step != 0) continue;
    if (r.only == Only::Frame && !ends_frame) continue;
    if (r.only == Only::Draw && !draws) continue;
    return true;
  }
  return false;
}

}  // namespace passim
