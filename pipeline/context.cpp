// Context: construction, the plumbing every entry point goes through (recording, compiling
// into display lists: PASSIM_ENTRY and intercept), the raster lanes, and passes
// (EXT_debug_marker). The entry points live by the spec's state groups in the other
// context_*.cpp files (docs/architecture.md).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "pipeline/checked_size.hpp"
#include "pipeline/context.hpp"
#include "pipeline/context_scratch.hpp"
#include "pipeline/fixed_point.hpp"
#include "stages/accumulate.hpp"
#include "stages/clear.hpp"

namespace passim {

namespace {
// The framebuffer's planes charged to the budget before they are allocated.
const FramebufferConfig& charge_planes(MemoryBudget& budget, const FramebufferConfig& config) {
  budget.charge(config.plane_bytes(), fmt::format("a {}x{} framebuffer", config.width, config.height));
  return config;
}
}  // namespace

Context::Context(const FramebufferConfig& config, const MachineProfile& profile, std::uint64_t memory_limit)
    : memory_(memory_limit), fb_(charge_planes(memory_, config)), profile_(profile), scratch_(std::make_unique<Scratch>(fb_, config.width)) {
  viewport_.width = config.width;
  viewport_.height = config.height;
  fragment_.scissor_width = config.width;
  fragment_.scissor_height = config.height;
  fb_control_.draw_buffer = config.double_buffer ? GL_BACK : GL_FRONT;
  pixel_.read_buffer = fb_control_.draw_buffer;
  draw_buffer_ids_ = buffers_named(fb_control_.draw_buffer);
  lighting_.lights.resize(static_cast<std::size_t>(profile_.limits.max_lights));
  lighting_.lights[0].diffuse = Vec4(1.0);
  lighting_.lights[0].specular = Vec4(1.0);
  textures_.gen[0].object_plane = textures_.gen[0].eye_plane = Vec4(1.0, 0.0, 0.0, 0.0);  // §2.10.4 defaults
  textures_.gen[1].object_plane = textures_.gen[1].eye_plane = Vec4(0.0, 1.0, 0.0, 0.0);
  transfer_.minmax.reset();
  update_fragment_bits();
  scratch_->stages.ops.configure(fragment_ops_input());
}

Context::~Context() = default;

void Context::set_threads(int threads) {
  run_raster_queue();
  primitive_setup_valid_ = false;  // connected to this thread's stages, or not
  threads = std::clamp(threads, 1, kMaxThreads);
  if (threads == this->threads()) return;
  scratch_->lanes.reset();
  if (threads > 1) {
    scratch_->lanes = std::make_unique<RasterLanes>(fb_, threads);
    scratch_->lanes->set_row_splitter(rows_on_lanes());
  }
}

int Context::threads() const { return scratch_->lanes ? scratch_->lanes->lanes() : 1; }

void Context::run_raster_queue() {
  raster_queued_ = false;
  if (scratch_->lanes) scratch_->lanes->flush(counters());
}

void Context::update_fragment_bits() {
  fragment_bits_ = fb_.config.color_bits;
  // A26: with fewer than 2 alpha bits, alpha is carried at the RGB precision.
  if (fragment_bits_[3] < 2) fragment_bits_[3] = std::max({fragment_bits_[0], fragment_bits_[1], fragment_bits_[2]});
}
// ---------------------------------------------------------------- recording and lists

namespace {

// The largest client-array element a call that reads the arrays reads (calls.hpp), in 64 bits;
// -1 when it reads none.
std::int64_t last_array_element(const CallInfo& info, const std::vector<Value>& values) {
  auto arg = [&](const char* name) { return values[static_cast<std::size_t>(info.param_index(name))]; };
  if (info.param_index("i") >= 0) return arg("i").i;
  if (info.param_index("indices") >= 0) {
    const Value& v = arg("indices");
    const std::byte* p = v.bytes ? v.bytes->data() : nullptr;
    std::int64_t last = -1;
    for (std::size_t k = 0; p && k < v.count; ++k) {
      std::uint32_t idx = 0;
      if (v.elem_type == GL_UNSIGNED_BYTE) idx = static_cast<std::uint8_t>(p[k]);
      else if (v.elem_type == GL_UNSIGNED_SHORT) { std::uint16_t s; std::memcpy(&s, p + 2 * k, 2); idx = s; }
      else std::memcpy(&idx, p + 4 * k, 4);
      last = std::max<std::int64_t>(last, idx);
    }
    return last;
  }
  return arg("count").i > 0 ? arg("first").i + arg("count").i - 1 : -1;
}

// The client-array elements such a call reads, in order; their count has been bounded by the
// array extents (check_array_bounds of last_array_element) before this is called.
std::vector<int> array_elements(const CallInfo& info, const std::vector<Value>& values) {
  std::vector<int> elements;
  if (const int i = info.param_index("i"); i >= 0) {
    elements.push_back(static_cast<int>(values[static_cast<std::size_t>(i)].i));
  } else if (const int indices = info.param_index("indices"); indices >= 0) {
    const Value& v = values[static_cast<std::size_t>(indices)];
    const std::byte* p = v.bytes ? v.bytes->data() : nullptr;
    for (std::size_t k = 0; p && k < v.count; ++k) {
      std::uint32_t idx = 0;
      if (v.elem_type == GL_UNSIGNED_BYTE) idx = static_cast<std::uint8_t>(p[k]);
      else if (v.elem_type == GL_UNSIGNED_SHORT) { std::uint16_t s; std::memcpy(&s, p + 2 * k, 2); idx = s; }
      else std::memcpy(&idx, p + 4 * k, 4);
      elements.push_back(static_cast<int>(idx));
    }
  } else {
    const std::int64_t first = values[static_cast<std::size_t>(info.param_index("first"))].i;
    const std::int64_t count = values[static_cast<std::size_t>(info.param_index("count"))].i;
    for (std::int64_t k = 0; k < count; ++k) elements.push_back(static_cast<int>(first + k));
  }
  return elements;
}

}  // namespace

bool Context::intercept_values(const CallInfo& info, std::vector<Value>&& values) {
  // A call that reads the client arrays reads nothing past the data a trace gave for them
  // (before anything is built from its count).
  const std::int64_t last_element = info.reads_client_arrays ? last_array_element(info, values) : -1;
  if (last_element >= 0 && (sink_ || (compiling_list_ != 0 && info.compiled_into_lists)))
    check_array_bounds(last_element);
  if (sink_ && !info.recorded_at_draw()) {
    if (in_begin_ && info.reads_client_arrays && last_element >= 0) {
      // §2.6.3: no pointer call may come between Begin and End, so an ArrayElement there is
      // recorded as the calls it amounts to, as a list compiles it.
      std::vector<Call> calls;
      compile_array_element(static_cast<int>(last_element), calls);
      for (const Call& call : calls) sink_->on_call(call);
    } else {
      // Vertex arrays are recorded with the data each draw reads (apitrace does the same).
      if (last_element >= 0) record_client_arrays(static_cast<int>(last_element));
      sink_->on_call(Call{&info, values});
    }
  }
  if (compiling_list_ == 0 || !info.compiled_into_lists) return false;
  const std::size_t compiled_before = compiling_calls_.size();
  if (info.reads_client_arrays) {
    // §5.4: vertex-array commands are compiled with their data dereferenced: as the
    // equivalent Begin / per-element calls / End (ArrayElement: the per-element calls alone).
    std::vector<Call>& out = compiling_calls_;
    const std::vector<int> elements = array_elements(info, values);
    const int mode = info.param_index("mode");
    if (mode < 0) {
      for (int i : elements) compile_array_element(i, out);
    } else if (info.param_index("first") < 0 || values[static_cast<std::size_t>(info.param_index("count"))].i >= 0) {
      static const CallInfo& begin = call_info_or_die("glBegin");
      static const CallInfo& end = call_info_or_die("glEnd");
      out.push_back(Call{&begin, {values[static_cast<std::size_t>(mode)]}});
      for (int i : elements) compile_array_element(i, out);
      out.push_back(Call{&end, {}});
    }
  } else {
    compiling_calls_.push_back(Call{&info, std::move(values)});
  }
  // The list's new calls are charged to the budget (§2.5: OUT_OF_MEMORY, the call not compiled).
  std::uint64_t added = 0;
  for (std::size_t k = compiled_before; k < compiling_calls_.size(); ++k)
    added += sizeof(Call) + call_bytes(compiling_calls_[k]);
  if (memory_.try_charge(added)) {
    compiling_bytes_ += added;
  } else {
    compiling_calls_.resize(compiled_before);
    set_error(GL_OUT_OF_MEMORY);
  }
  return compile_mode_ == GL_COMPILE;
}
// ---------------------------------------------------------------- passes (EXT_debug_marker)

Counters& Context::counters() {
  if (current_pass_ == SIZE_MAX) {
    passes_.push_back(Pass{"(unmarked)", static_cast<int>(marker_stack_.size()), {}});
    current_pass_ = passes_.size() - 1;
  }
  Counters* c = &passes_[current_pass_].counters;
  scratch_->counters = c;
  return *c;
}

void Context::glPushGroupMarkerEXT(GLsizei length, const GLchar* marker) {
  PASSIM_ENTRY(length, marker)
  if (length < 0) return set_error(GL_INVALID_VALUE);
  std::string label = marker ? (length == 0 ? std::string(marker) : std::string(marker, strnlen(marker, static_cast<std::size_t>(length)))) : "";
  passes_.push_back(Pass{label, static_cast<int>(marker_stack_.size()), {}});
  marker_stack_.push_back(passes_.size() - 1);
  current_pass_ = passes_.size() - 1;
}

void Context::glPopGroupMarkerEXT() {
  PASSIM_ENTRY()
  if (marker_stack_.empty()) {
    warn_once("glPopGroupMarkerEXT without a matching push: ignored");
    return;
  }
  const std::size_t ended = marker_stack_.back();
  marker_stack_.pop_back();
  // Work after the pop belongs to the enclosing marker, as a new segment of it.
  if (marker_stack_.empty()) {
    current_pass_ = SIZE_MAX;
  } else {
    const Pass& outer = passes_[marker_stack_.back()];
    passes_.push_back(Pass{outer.label, outer.depth, {}});
    marker_stack_.back() = passes_.size() - 1;
    current_pass_ = marker_stack_.back();
  }
  if (pass_end_) pass_end_(*this, ended);  // the raster queue ran at PASSIM_ENTRY: the planes are complete
}

void Context::glInsertEventMarkerEXT(GLsizei length, const GLchar* marker) {
  PASSIM_ENTRY(length, marker)
  if (length < 0) set_error(GL_INVALID_VALUE);
}

Counters Context::total_counters() const {
  Counters total;
  for (const Pass& p : passes_) total += p.counters;
  return total;
}

void Context::check_balance() const {
  for (const Pass& p : passes_) {
    std::string err = p.counters.balance_error();
    if (!err.empty()) throw InternalError(fmt::format("pass \"{}\": {}", p.label, err));
  }
}

void Context::swap_buffers() {
  primitive_setup_valid_ = false;
  if (!fb_.config.double_buffer) return;
  fb_.color[0].rgba = fb_.color[1].rgba;  // the back buffer's content is kept (GLX leaves it undefined)
}

}  // namespace passim
