#include "trace_io/call_runner.hpp"

#include <fmt/format.h>


#include "pipeline/checked_size.hpp"
#include "pipeline/gl.hpp"
#include "client/pixel_unpack.hpp"

namespace passim {

namespace {
[[noreturn]] void reject(const std::string& message) { throw CallRejected(message); }
}  // namespace

// Every array argument must hold what its row's length rule says the call reads (under the
// current unpack modes for images and bitmaps), so the GL never reads past a trace's data.
void CallRunner::check_lengths(const CallInfo& info, const std::vector<Value>& values) const {
  for (std::size_t k = 0; k < info.params.size(); ++k) {
    const CallInfo::Param& p = info.params[k];
    if (!p.is_array() || p.length == Length::Any) continue;
    const Value& v = values[k];
    const bool null = !v.bytes || v.count == 0;
    // No data: the GL reads nothing, so what the unpack modes would address does not matter
    // (and its size may overflow: the call's own checks, e.g. a width beyond the maximum, then
    // raise the GL error).
    if (p.kind != 'O' && null && param_may_be_null(p)) continue;
    std::uint64_t need = 0;
    try {
      need = param_elements_needed(info, k, values, ctx_.unpack_store());
    } catch (const SizeOverflow&) {
      reject(fmt::format("{}: the size of argument {} ({}) overflows 64 bits under the current pixel-store modes",
                         info.name, k + 1, p.name));
    }
    if (p.kind == 'O') {
      // Output arguments are written into a fixed scratch area when a query runs.
      if (need > kOutputScratchElements)
        reject(fmt::format("{}: argument {} ({}) would receive {} values; a trace may ask for at most {}", info.name,
                           k + 1, p.name, need, kOutputScratchElements));
      continue;
    }
    if (v.count < need) {
      const bool image = p.length == Length::Image || p.length == Length::Bitmap;
      reject(fmt::format("{}: argument {} ({}) needs {} values{}, the trace gives {}", info.name, k + 1, p.name, need,
                         image ? " under the current unpack modes" : "", v.count));
    }
  }
}

void CallRunner::run(const CallInfo& info, const std::vector<Value>& values, const std::string& where) {
  check_lengths(info, values);
  ctx_.set_source_location(where);
  if (info.query) return;  // queries change nothing; their output arguments cannot be replayed
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
