#include "trace_io/call_runner.hpp"

#include <algorithm>

#include <fmt/format.h>


#include "pipeline/checked_size.hpp"
#include "pipeline/gl.hpp"
#include "client/pixel_unpack.hpp"
#include "trace_io/query_log.hpp"

namespace passim {

namespace {
[[noreturn]] void reject(const std::string& message) { throw CallRejected(message); }
// Bytes of room per output value: the widest element a call writes (GLdouble).
constexpr std::uint64_t kOutputRoomPerElement = 8;
}  // namespace

// Every array argument must hold what its row's length rule says the call reads (under the
// current unpack modes for images and bitmaps), so the GL never reads past a trace's data; every
// output argument gets the room its rule says the call writes.
std::vector<std::uint64_t> CallRunner::check_lengths(const CallInfo& info, const std::vector<Value>& values) const {
  std::vector<std::uint64_t> outputs(info.params.size(), 0);
  for (std::size_t k = 0; k < info.params.size(); ++k) {
    const CallInfo::Param& p = info.params[k];
    if (!p.is_array() || (p.length == Length::Any && p.kind != 'O')) continue;
    const Value& v = values[k];
    const bool null = !v.bytes || v.count == 0;
    // No data: the GL reads nothing, so what the unpack modes would address does not matter
    // (and its size may overflow: the call's own checks, e.g. a width beyond the maximum, then
    // raise the GL error).
    if (p.kind != 'O' && null && param_may_be_null(p)) continue;
    std::uint64_t need = 0;
    try {
      need = p.kind == 'O' ? output_elements_needed(info, k, values, ctx_) : param_elements_needed(info, k, values, ctx_.unpack_store());
    } catch (const SizeOverflow&) {
      reject(fmt::format("{}: the size of argument {} ({}) overflows 64 bits under the current pixel-store modes",
                         info.name, k + 1, p.name));
    }
    if (p.kind == 'O') {
      // The room is the replayer's memory, within what the budget leaves.
      if (need > ctx_.memory().left() / kOutputRoomPerElement)
        reject(fmt::format("{}: argument {} ({}) would receive {} values, more than the memory budget leaves room for "
                           "(--max-memory)",
                           info.name, k + 1, p.name, need));
      outputs[k] = need;
      continue;
    }
    if (v.count < need) {
      const bool image = p.length == Length::Image || p.length == Length::Bitmap;
      reject(fmt::format("{}: argument {} ({}) needs {} values{}, the trace gives {}", info.name, k + 1, p.name, need,
                         image ? " under the current unpack modes" : "", v.count));
    }
  }
  return outputs;
}

void CallRunner::run(const CallInfo& info, const std::vector<Value>& values, const std::string& where) {
  const std::vector<std::uint64_t> needed = check_lengths(info, values);
  ctx_.set_source_location(where);
  if (info.has_outputs() || info.returns_value) {
    run_with_outputs(info, values, needed, where);
    report_errors();
    return;
  }
  const std::size_t client_depth = ctx_.client_attrib_depth();
  const GLbitfield client_top = ctx_.client_attrib_top_mask();
  try {
    info.invoke(ctx_, values);
  } catch (const ClientDataError& e) {
    reject(e.what());
  }
  // PushClientAttrib saved the arrays' pointers: their data stays alive until the pop, which
  // brings back the data they read when it restores the arrays (CLIENT_VERTEX_ARRAY_BIT).
  if (ctx_.client_attrib_depth() > client_depth) {
    saved_keep_alive_.push_back(keep_alive_);
  } else if (ctx_.client_attrib_depth() < client_depth && !saved_keep_alive_.empty()) {
    if (client_top & GL_CLIENT_VERTEX_ARRAY_BIT) keep_alive_ = std::move(saved_keep_alive_.back());
    saved_keep_alive_.pop_back();
  }
  if (info.recorded_at_draw()) {
    const Value& data = values.back();
    const void* pointer = data.bytes ? static_cast<const void*>(data.bytes->data()) : nullptr;
    for (GLenum array : ctx_.adopt_client_array_data(pointer, data.bytes ? data.bytes->size() : 0))
      keep_alive_[array] = data.bytes;  // the array's previous data is no longer read
  }
  report_errors();
}

void CallRunner::run_with_outputs(const CallInfo& info, const std::vector<Value>& values,
                                  const std::vector<std::uint64_t>& needed, const std::string& where) {
  // Each output argument points at room of its own (zeroed: what the GL leaves unwritten reads
  // as 0), at least 16 values of the widest element (a glGet* of a matrix), whatever the rule.
  CallResults results;
  std::vector<Value> args = values;
  for (std::size_t k = 0; k < info.params.size(); ++k) {
    if (info.params[k].kind != 'O') continue;
    CallOutput out;
    out.param = k;
    out.type = param_element_type(info, k, values);
    out.elements = needed[k];
    out.bytes.assign((std::max<std::uint64_t>(needed[k], 16)) * kOutputRoomPerElement, std::byte{0});
    args[k].i = static_cast<std::int64_t>(results.outputs.size());
    results.outputs.push_back(std::move(out));
  }
  const std::size_t errors_before = ctx_.error_log().size();
  run_collecting(info, ctx_, args, results);
  const auto& log = ctx_.error_log();
  if (queries_) queries_->add(where, info, values, results, log.size() > errors_before ? log[errors_before].error : 0);
}

void CallRunner::report_errors() {
  const auto& log = ctx_.error_log();
  for (; reported_errors_ < log.size(); ++reported_errors_) {
    const GlErrorRecord& e = log[reported_errors_];
    std::string msg = fmt::format("{} raised by {}", enum_name(e.error), e.call);
    if (diagnostics_) *diagnostics_ << fmt::format("{}: {}\n", e.where, msg);
    if (strict_) reject(msg + " (--strict)");
  }
}

}  // namespace passim
