// Running one parsed call on a context, with the checks that every trace reader
// (.pass text, apitrace binary) shares: data long enough for what the call reads,
// client-array extents, output arguments given room (queries run with their side effects,
// their results logged for --queries), GL errors reported.
#pragma once
#include <map>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "pipeline/calls.hpp"
#include "pipeline/context.hpp"

namespace passim {

// A call whose data cannot be replayed (fewer values than it reads), or a GL error
// under `strict`: the reader adds its location.
struct CallRejected : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class CallRunner {
 public:
  // `diagnostics` (may be null) receives each GL error as "where: GL_x raised by call".
  CallRunner(Context& ctx, bool strict, std::ostream* diagnostics) : ctx_(ctx), strict_(strict), diagnostics_(diagnostics) {}
  // `where` locates the call in messages and the context's error log.
  void run(const CallInfo& info, const std::vector<Value>& values, const std::string& where);
  // Reports the GL errors raised since the last report (after drawing outside run()).
  void report_errors();
  // Where the results of every call that returns a value or writes an output go (may be null).
  void set_query_log(class QueryLog* log) { queries_ = log; }

 private:
  // Refuses data shorter than the call reads; returns the elements each output parameter
  // receives (0 for the others).
  std::vector<std::uint64_t> check_lengths(const CallInfo& info, const std::vector<Value>& values) const;
  void run_with_outputs(const CallInfo& info, const std::vector<Value>& values, const std::vector<std::uint64_t>& needed,
                        const std::string& where);

  Context& ctx_;
  bool strict_;
  std::ostream* diagnostics_;
  std::size_t reported_errors_ = 0;
  class QueryLog* queries_ = nullptr;
  std::map<GLenum, std::shared_ptr<const std::vector<std::byte>>> keep_alive_;  // client arrays in use
  std::vector<std::map<GLenum, std::shared_ptr<const std::vector<std::byte>>>> saved_keep_alive_;  // per client push
};

}  // namespace passim
