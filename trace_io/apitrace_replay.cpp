#include "trace_io/apitrace_replay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "trace_io/apitrace_reader.hpp"
#include "trace_io/call_runner.hpp"
#include "pipeline/calls.hpp"

namespace passim {

namespace {

using RecordedValue = apitrace::Value;
using Kind = apitrace::Value::Kind;

// GLX 1.4 §3.3.3 attribute tokens (GL/glx.h).
enum : std::int64_t {
  kGlxUseGl = 1, kGlxRgba = 4, kGlxDoubleBuffer = 5, kGlxStereo = 6, kGlxRedSize = 8, kGlxGreenSize = 9,
  kGlxBlueSize = 10, kGlxAlphaSize = 11, kGlxDepthSize = 12, kGlxStencilSize = 13, kGlxAccumRedSize = 14,
  kGlxAccumAlphaSize = 17
};
constexpr std::int64_t kGlxDontCare = 0xFFFFFFFF;

// What the program asked of its visual (glXChooseVisual / glXChooseFBConfig).
struct VisualRequest {
  bool known = false;
  bool double_buffer = false;
  int color = 0, alpha = 0, depth = 0, stencil = 0, accum = 0;
};

// Window-system calls with no effect on the framebuffer's contents.
const std::set<std::string, std::less<>>& harmless_window_calls() {
  static const std::set<std::string, std::less<>> names = {
      "glXCreateContext", "glXCreateNewContext", "glXCreateContextAttribsARB", "glXMakeCurrent",
      "glXMakeContextCurrent", "glXDestroyContext", "glXQueryExtension", "glXQueryVersion",
      "glXQueryExtensionsString", "glXQueryServerString", "glXGetClientString", "glXGetProcAddress",
      "glXGetProcAddressARB", "glXGetConfig", "glXGetFBConfigAttrib", "glXGetFBConfigs", "glXGetVisualFromFBConfig",
      "glXIsDirect", "glXGetCurrentContext", "glXGetCurrentDrawable", "glXGetCurrentDisplay",
      "glXGetCurrentReadDrawable", "glXWaitGL", "glXWaitX", "glXQueryDrawable", "glXCreateWindow",
      "glXDestroyWindow", "glXSwapIntervalEXT", "glXSwapIntervalMESA", "glXSwapIntervalSGI", "glXSelectEvent",
      "glXGetSelectedEvent", "glXQueryContext"};
  return names;
}

// A call the table does not know whose name says it only asks (GL's naming of queries: glGet*,
// glIs*, glAreTexturesResident): it changes nothing, so skipping it changes no image.
bool named_as_query(std::string_view fn) {
  return fn.starts_with("glGet") || fn.starts_with("glIs") || fn == "glAreTexturesResident";
}

struct Stop {
  std::string message;
};

class ApitraceReplayer {
 public:
  ApitraceReplayer(std::string name, const ApitraceOptions& options) : name_(std::move(name)), options_(options) {}

  ApitraceReplay run(std::istream& in) {
    try {
      // The reader holds a quarter of the run's budget at most (its values are converted and dropped).
      apitrace::Reader reader(in, options_.max_memory / 4);
      while (std::optional<apitrace::Call> call = reader.next()) {
        ++out_.calls;
        process(*call);
      }
      if (!out_.result.context) throw Stop{fmt::format("{}: the trace makes no GL call to replay", name_)};
      out_.result.context->check_balance();
    } catch (const apitrace::FormatError& e) {
      out_.error = fmt::format("{}: {}", name_, e.what());
    } catch (const Stop& s) {
      out_.error = s.message;
    } catch (const TraceError& e) {
      out_.error = e.what();
    } catch (const std::bad_alloc&) {
      out_.error = fmt::format("{}: call {}: out of memory (--max-memory sets the run's budget)", name_, out_.calls);
    } catch (const std::exception& e) {  // any other failure still names the call
      out_.error = fmt::format("{}: call {}: {}", name_, out_.calls, e.what());
    }
    auto by_first_call = [](const SkippedCall& a, const SkippedCall& b) { return a.first_call < b.first_call; };
    for (auto* list : {&unsupported_, &ignored_}) {
      auto& target = list == &unsupported_ ? out_.unsupported : out_.ignored;
      for (auto& [fn, skipped] : *list) target.push_back(skipped);
      std::sort(target.begin(), target.end(), by_first_call);
    }
    std::vector<SkippedCall>& all = out_.result.skipped;
    all = out_.unsupported;
    all.insert(all.end(), out_.ignored.begin(), out_.ignored.end());
    std::sort(all.begin(), all.end(), by_first_call);
    if (options_.diagnostics) *options_.diagnostics << skipped_lines(all);
    return std::move(out_);
  }

 private:
  [[noreturn]] void stop(const apitrace::Call& call, const std::string& message) const {
    throw Stop{fmt::format("{}: call {}: {}", name_, call.number, message)};
  }

  void skip(std::map<std::string, SkippedCall>& list, const apitrace::Call& call, const std::string& why) {
    auto [it, fresh] = list.try_emplace(call.name());
    if (fresh) it->second = SkippedCall{call.name(), 0, call.number, why};
    ++it->second.count;
  }

  void process(const apitrace::Call& call) {
    const std::string& fn = call.name();
    if (fn.starts_with("glX")) {
      window_system(call);
      return;
    }
    const CallInfo* info = find_call(fn);
    replay_gl(call, info);
    const bool flush = fn == "glFlush" || fn == "glFinish";
    const bool draws = info && info->draws;
    if (out_.result.context && ((options_.snapshot && options_.snapshot->contains(call.number, false, draws)) ||
                                (options_.snapshot_at_flush && flush)))
      snapshot(call.number, false);
  }

  void replay_gl(const apitrace::Call& call, const CallInfo* info) {
    const std::string& fn = call.name();
    if (!info) {
      if (named_as_query(fn)) {
        skip(ignored_, call, "a query: no effect on the image");
        return;
      }
      skip(unsupported_, call, "not modelled by passim");
      if (options_.strict) stop(call, fmt::format("{} is not modelled by passim (--strict)", fn));
      return;
    }
    if (call.args.size() != info->params.size())
      stop(call, fmt::format("{} is recorded with {} arguments; it takes {}", fn, call.args.size(),
                             info->params.size()));
    std::vector<Value> values;
    for (std::size_t k = 0; k < call.args.size(); ++k) values.push_back(convert(call, *info, k, values));
    ensure_context(call, fn == "glViewport" ? &values : nullptr);
    try {
      runner_->run(*info, values, fmt::format("{}: call {}", name_, call.number));
    } catch (const CallRejected& e) {
      stop(call, e.what());
    }
  }

  // ---------------------------------------------------------------- window system

  void window_system(const apitrace::Call& call) {
    const std::string& fn = call.name();
    if (fn == "glXChooseVisual" || fn == "glXChooseFBConfig" || fn == "glXChooseFBConfigSGIX") {
      if (call.args.size() < 3 || !call.args[2]) stop(call, fmt::format("{} without its attribute list", fn));
      if (!out_.result.context) visual_ = parse_attributes(call, *call.args[2], fn == "glXChooseVisual");
      return;
    }
    if (fn == "glXSwapBuffers") {
      ++out_.frames;  // the back buffer is copied to the front
      if (!out_.result.context) return;
      out_.result.context->swap_buffers();
      if (options_.record) options_.record->swap();
      if (options_.snapshot && options_.snapshot->contains(call.number, true, false)) snapshot(call.number, true);
      return;
    }
    if (harmless_window_calls().count(fn)) {
      skip(ignored_, call, "window system: no effect on the framebuffer");
      return;
    }
    skip(unsupported_, call, "window-system call not modelled by passim");
    if (options_.strict) stop(call, fmt::format("{} is not modelled by passim (--strict)", fn));
  }

  VisualRequest parse_attributes(const apitrace::Call& call, const RecordedValue& list, bool choose_visual) {
    VisualRequest v;
    v.known = true;
    v.double_buffer = !choose_visual;  // glXChooseFBConfig: GLX_DONT_CARE, and Mesa lists double first
    if (list.kind == Kind::Null) return v;
    if (list.kind != Kind::Array) stop(call, "the visual attribute list is not an array");
    std::vector<std::int64_t> a;
    for (const RecordedValue& item : list.items) {
      if (!item.is_integer()) stop(call, "a visual attribute is not an integer");
      a.push_back(item.as_integer());
    }
    auto size_of = [](std::int64_t x) {
      return x == kGlxDontCare || x < 0 ? 0 : static_cast<int>(std::min<std::int64_t>(x, 64));
    };
    for (std::size_t k = 0; k < a.size() && a[k] != 0; ++k) {
      const std::int64_t token = a[k];
      const bool flag_only = choose_visual && (token == kGlxUseGl || token == kGlxRgba || token == kGlxDoubleBuffer ||
                                               token == kGlxStereo);
      const std::int64_t value = flag_only ? 1 : (k + 1 < a.size() ? a[++k] : 0);
      switch (token) {
        case kGlxDoubleBuffer: v.double_buffer = value == 1 || value == kGlxDontCare; break;
        case kGlxRedSize: case kGlxGreenSize: case kGlxBlueSize: v.color = std::max(v.color, size_of(value)); break;
        case kGlxAlphaSize: v.alpha = size_of(value); break;
        case kGlxDepthSize: v.depth = size_of(value); break;
        case kGlxStencilSize: v.stencil = size_of(value); break;
        default:
          if (token >= kGlxAccumRedSize && token <= kGlxAccumAlphaSize) v.accum = std::max(v.accum, size_of(value));
          break;
      }
    }
    return v;
  }

  // The framebuffer: the profile's widths (GLX 1.4 §3.3.3: "the largest available" of at
  // least the size asked for; none where none is asked for), the overrides, and the size of
  // the drawable as apitrace records it (its fake glViewport at glXMakeCurrent).
  void ensure_context(const apitrace::Call& call, const std::vector<Value>* viewport) {
    if (out_.result.context) return;
    const MachineProfile* profile = find_profile(options_.profile);
    if (!profile) stop(call, fmt::format("unknown machine profile '{}' (see 'passim info')", options_.profile));
    FramebufferConfig f;
    f.color_bits = profile->color_bits;
    f.depth_bits = profile->depth_bits;
    f.stencil_bits = profile->stencil_bits;
    f.accum_bits = profile->accum_bits;
    if (visual_.known) {
      for (int c = 0; c < 3; ++c) f.color_bits[static_cast<std::size_t>(c)] = std::max(f.color_bits[static_cast<std::size_t>(c)], visual_.color);
      f.color_bits[3] = visual_.alpha > 0 ? std::max(f.color_bits[0], visual_.alpha) : 0;
      f.depth_bits = visual_.depth > 0 ? std::max(f.depth_bits, visual_.depth) : 0;
      f.stencil_bits = visual_.stencil > 0 ? std::max(f.stencil_bits, visual_.stencil) : 0;
      f.double_buffer = visual_.double_buffer;
    }
    if (options_.color_bits > 0) {
      const bool alpha = f.color_bits[3] > 0;
      f.color_bits = {options_.color_bits, options_.color_bits, options_.color_bits, alpha ? options_.color_bits : 0};
    }
    f.accum_bits = FramebufferConfig::default_accum_bits(f.color_bits);
    if (visual_.known && visual_.accum == 0) f.accum_bits = 0;
    if (visual_.known && visual_.accum > 0) f.accum_bits = std::max(f.accum_bits, visual_.accum);
    if (options_.depth_bits >= 0) f.depth_bits = options_.depth_bits;
    if (options_.stencil_bits >= 0) f.stencil_bits = options_.stencil_bits;
    if (options_.accum_bits >= 0) f.accum_bits = options_.accum_bits;
    if (options_.width > 0) {
      f.width = options_.width;
      f.height = options_.height;
    } else if (viewport) {
      const std::int64_t w = (*viewport)[2].i, h = (*viewport)[3].i;
      if (w <= 0 || h <= 0 || w > 1 << 20 || h > 1 << 20)
        stop(call, fmt::format("the first glViewport is {}x{}: not a window size; give --size WxH", w, h));
      f.width = static_cast<int>(w);
      f.height = static_cast<int>(h);
    } else {
      stop(call, fmt::format("{} comes before any glViewport, so the window size is unknown; give --size WxH",
                             call.name()));
    }
    TraceSettings& s = out_.result.settings;
    s.profile = options_.profile;
    s.framebuffer = f;
    s.subpixel_bits = options_.subpixel_bits;
    const MachineProfile m = s.machine();
    if (m.limits.subpixel_bits < 0 || m.limits.subpixel_bits > 12) stop(call, "--subpixel takes 0..12");
    const std::string err = f.validate(m.limits.max_framebuffer_size);
    if (!err.empty()) stop(call, err);
    try {
      out_.result.context = std::make_unique<Context>(f, m, options_.max_memory);
    } catch (const BudgetExceeded& e) {
      stop(call, e.what());
    }
    out_.result.context->set_pass_end_observer(options_.pass_end);
    runner_ = std::make_unique<CallRunner>(*out_.result.context, options_.strict, options_.diagnostics);
    runner_->set_query_log(options_.queries);
    if (options_.record) {
      options_.record->write_header(s);
      out_.result.context->set_call_sink(options_.record);
    }
  }

  // ---------------------------------------------------------------- values

  // A recorded argument as the call table's parameter wants it, read exactly.
  Value convert(const apitrace::Call& call, const CallInfo& info, std::size_t k, const std::vector<Value>& done) {
    const CallInfo::Param& p = info.params[k];
    Value v;
    if (p.kind == 'O') return v;
    const std::string arg_name = k < call.sig->arg_names.size() ? call.sig->arg_names[k] : std::string();
    auto bad = [&](const std::string& what) -> Value {
      stop(call, fmt::format("{}: argument {} ({}) {}", info.name, k + 1, arg_name, what));
    };
    if (!call.args[k]) return bad("was not recorded");
    const RecordedValue* a = &*call.args[k];
    if (a->kind == Kind::Repr && a->items.size() == 2) a = &a->items[1];
    switch (p.kind) {
      case 'e': case 'm': case 'n': case 'b': case 'k': case 'x': case 'z': case 'i': case 'u': case 'c': case 'g': case 'h':
      case 'w': {
        if (!a->is_integer()) return bad("is not an integer or enum");
        const std::int64_t x = a->as_integer();
        const IntegerRange range = integer_range(p.kind);
        if (x < range.lo || x > range.hi) return bad(fmt::format("= {} is out of its type's range", x));
        v.i = x;
        return v;
      }
      case 'f': case 'y':
        if (!a->is_number()) return bad("is not a number");
        // A GLfloat is recorded as a float: widened exactly, it narrows back exactly.
        v.d = static_cast<double>(static_cast<float>(a->as_double()));
        return v;
      case 'd':
        if (!a->is_number()) return bad("is not a number");
        v.d = a->as_double();
        return v;
      case 's':
        if (a->kind == Kind::Null) return v;
        if (a->kind != Kind::String && a->kind != Kind::Blob) return bad("is not a string");
        v.set_str(a->bytes);
        return v;
      default:
        break;
    }
    // Arrays.
    const GLenum type = param_element_type(info, k, done);
    const int size = type_size(type);
    if (size == 0) return bad(fmt::format("has an unknown data type {}", enum_name(type)));
    v.elem_type = type;
    auto bytes = std::make_shared<std::vector<std::byte>>();
    if (a->kind == Kind::Null) {
      v.count = 0;
    } else if (a->kind == Kind::Blob || a->kind == Kind::String) {
      bytes->resize(a->bytes.size());
      std::memcpy(bytes->data(), a->bytes.data(), a->bytes.size());
      v.count = a->bytes.size() / static_cast<std::size_t>(size);
    } else if (a->kind == Kind::Array) {
      bytes->resize(a->items.size() * static_cast<std::size_t>(size));
      for (std::size_t e = 0; e < a->items.size(); ++e) {
        const RecordedValue& item = a->items[e];
        if (!item.is_number()) return bad(fmt::format("element {} is not a number", e + 1));
        store(bytes->data() + e * static_cast<std::size_t>(size), type, item);
      }
      v.count = a->items.size();
    } else if (a->kind == Kind::Pointer) {
      return bad("points into the program's memory, which apitrace did not record (a buffer-object offset?)");
    } else {
      return bad("is not an array");
    }
    v.bytes = std::move(bytes);
    return v;  // its length is checked against the call's row when it runs (CallRunner)
  }

  // One array element at the element type, as the program's memory held it.
  static void store(std::byte* dst, GLenum type, const RecordedValue& x) {
    auto put = [dst](auto value) { std::memcpy(dst, &value, sizeof value); };
    switch (type) {
      case GL_FLOAT: put(static_cast<float>(x.as_double())); break;
      case GL_DOUBLE: put(x.as_double()); break;
      case GL_INT: put(static_cast<std::int32_t>(x.as_integer())); break;
      case GL_UNSIGNED_INT: put(static_cast<std::uint32_t>(x.as_integer())); break;
      case GL_SHORT: put(static_cast<std::int16_t>(x.as_integer())); break;
      case GL_UNSIGNED_SHORT: put(static_cast<std::uint16_t>(x.as_integer())); break;
      case GL_BYTE: put(static_cast<std::int8_t>(x.as_integer())); break;
      default: put(static_cast<std::uint8_t>(x.as_integer())); break;
    }
  }

  // ---------------------------------------------------------------- snapshots

  // The draw buffer after call `number` (at a swap: the front buffer, which now shows the frame).
  void snapshot(std::uint64_t number, bool frame_end) {
    Context& ctx = *out_.result.context;
    GLenum buffer = frame_end ? GL_FRONT : ctx.draw_buffer();
    if (buffer == GL_FRONT_AND_BACK || buffer == GL_LEFT || buffer == GL_FRONT_LEFT) buffer = GL_FRONT;
    if (buffer == GL_BACK_LEFT) buffer = GL_BACK;
    if (!ctx.color_buffer(buffer)) return;  // GL_NONE: nothing is drawn, nothing to show
    const std::string name = fmt::format("{:010}", number);
    for (const CapturedImage& img : out_.result.images)
      if (img.name == name) return;
    const std::string plane = ctx.config().color_bits[3] > 0 ? "color" : "rgb";
    out_.result.images.push_back(capture_plane(ctx, name, plane, buffer));
    if (options_.record) options_.record->output(name, plane, enum_name(buffer, EnumRole::Buffer));
  }

  std::string name_;
  const ApitraceOptions& options_;
  ApitraceReplay out_;
  VisualRequest visual_;
  std::unique_ptr<CallRunner> runner_;
  std::map<std::string, SkippedCall> unsupported_, ignored_;
};

}  // namespace

ApitraceReplay replay_apitrace(std::istream& in, const std::string& name, const ApitraceOptions& options) {
  ApitraceReplayer r(name, options);
  return r.run(in);
}

ApitraceReplay replay_apitrace(const std::filesystem::path& file, const ApitraceOptions& options) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    ApitraceReplay r;
    r.error = fmt::format("{}: cannot open the file", file.string());
    return r;
  }
  return replay_apitrace(in, file.string(), options);
}

std::string skipped_summary(const ApitraceReplay& replay) { return skipped_lines(replay.result.skipped); }

bool looks_like_apitrace(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[2] = {0, 0};
  in.read(magic, 2);
  if (in.gcount() != 2) return false;
  return (magic[0] == 'a' && magic[1] == 't') ||
         (static_cast<unsigned char>(magic[0]) == 0x1f && static_cast<unsigned char>(magic[1]) == 0x8b);
}

}  // namespace passim
