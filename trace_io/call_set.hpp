// Call sets in apitrace's syntax (apitrace docs/USAGE.markdown "Call sets"), which
// choose the calls `passim run FILE.trace --snapshot` captures:
//   12            one call               40-50      a range (inclusive)
//   40-50/2       every 2nd call from 40  100-       from 100 on      *   every call
//   frame         the calls that end a frame (glXSwapBuffers)
//   draw          the calls that draw (glEnd, glDrawArrays, glClear, ...)
//   0-500/draw    those within a range    @FILE      the set written in FILE
// Items are separated by commas or white space.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace passim {

class CallSet {
 public:
  // Throws std::invalid_argument with a message naming the offending text.
  static CallSet parse(const std::string& text);
  bool empty() const { return ranges_.empty(); }
  bool contains(std::uint64_t call, bool ends_frame, bool draws) const;

 private:
  enum class Only { Any, Frame, Draw };
  struct Range {
    std::uint64_t first = 0, last = UINT64_MAX, step = 1;
    Only only = Only::Any;
  };
  std::vector<Range> ranges_;
};

}  // namespace passim
