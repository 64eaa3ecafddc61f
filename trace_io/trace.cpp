// .pass traces: parsing, replay and writing (docs/trace-format.md).
#include "trace_io/trace.hpp"

#include <algorithm>

#include <fmt/format.h>

#include <charconv>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>

#include "trace_io/call_runner.hpp"
#include "trace_io/obj_file.hpp"
#include "trace_io/side_files.hpp"
#include "pipeline/fixed_point.hpp"
#include "client/pixel_unpack.hpp"

namespace passim {

TraceError::TraceError(const std::string& f, int l, const std::string& m)
    : std::runtime_error(fmt::format("{}:{}: {}", f, l, m)), file(f), line(l), message(m) {}

// ------------------------------------------------------------------ settings

std::vector<std::string> TraceSettings::header_lines() const {
  const FramebufferConfig& f = framebuffer;
  std::vector<std::string> lines;
  lines.push_back(fmt::format("@profile {}", profile));
  lines.push_back(fmt::format("@framebuffer {}x{} color={},{},{},{} depth={} stencil={} accum={} double={}", f.width,
                              f.height, f.color_bits[0], f.color_bits[1], f.color_bits[2], f.color_bits[3],
                              f.depth_bits, f.stencil_bits, f.accum_bits, f.double_buffer ? "yes" : "no"));
  lines.push_back(fmt::format("@subpixel {}", machine().limits.subpixel_bits));
  return lines;
}

MachineProfile TraceSettings::machine() const {
  const MachineProfile* p = find_profile(profile);
  MachineProfile m = p ? *p : machine_profiles().front();
  if (subpixel_bits >= 0) m.limits.subpixel_bits = subpixel_bits;
  return m;
}

// ------------------------------------------------------------------ images

namespace {
constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull, kFnvPrime = 0x100000001b3ull;
}  // namespace

std::string fnv1a_hex(const std::vector<std::uint32_t>& codes, int bytes_per_code) {
  std::uint64_t h = kFnvOffset;
  for (std::uint32_t c : codes) {
    for (int b = 0; b < bytes_per_code; ++b) {
      h ^= (c >> (8 * b)) & 0xFFu;
      h *= kFnvPrime;
    }
  }
  return fmt::format("{:016x}", h);
}

std::uint64_t fnv1a(std::span<const std::byte> bytes) {
  std::uint64_t h = kFnvOffset;
  for (std::byte b : bytes) h = (h ^ static_cast<std::uint64_t>(b)) * kFnvPrime;
  return h;
}

CapturedImage capture_plane(const Context& ctx, const std::string& name, const std::string& plane, GLenum buffer,
                            CaptureRegion region) {
  const Framebuffer& fb = ctx.framebuffer();
  if (region.width == 0) region = {0, 0, fb.width(), fb.height()};
  CapturedImage img;
  img.name = name;
  img.plane = plane;
  img.width = region.width;
  img.height = region.height;
  // Copies `channels` codes per pixel of the region, starting at component `first` of
  // a plane stored with `stride` codes per pixel.
  auto copy_region = [&](const auto& codes, int stride, int first, int channels) {
    img.channels = channels;
    img.codes.assign(static_cast<std::size_t>(region.width) * static_cast<std::size_t>(region.height) *
                         static_cast<std::size_t>(channels), 0);
    if (codes.empty()) return;
    std::size_t k = 0;
    for (int y = region.y; y < region.y + region.height; ++y)
      for (int x = region.x; x < region.x + region.width; ++x)
        for (int c = 0; c < channels; ++c)
          img.codes[k++] = codes[fb.pixel_index(x, y) * static_cast<std::size_t>(stride) + static_cast<std::size_t>(first + c)];
  };
  if (plane == "color" || plane == "rgb" || plane == "alpha") {
    const ColorPlane* cp = ctx.color_buffer(buffer);
    img.buffer = enum_name(buffer, EnumRole::Buffer);
    if (plane == "color") {
      img.bits = fb.config.color_bits;
      copy_region(cp->rgba, 4, 0, 4);
    } else if (plane == "rgb") {
      img.bits = {fb.config.color_bits[0], fb.config.color_bits[1], fb.config.color_bits[2], 0};
      copy_region(cp->rgba, 4, 0, 3);
    } else {
      img.bits = {fb.config.color_bits[3], 0, 0, 0};
      copy_region(cp->rgba, 4, 3, 1);
    }
    img.hash = fnv1a_hex(img.codes, 2);
  } else if (plane == "depth") {
    img.bits = {fb.config.depth_bits, 0, 0, 0};
    copy_region(fb.depth, 1, 0, 1);
    img.hash = fnv1a_hex(img.codes, 4);
  } else {
    img.bits = {fb.config.stencil_bits, 0, 0, 0};
    copy_region(fb.stencil, 1, 0, 1);
    img.hash = fnv1a_hex(img.codes, 1);
  }
  return img;
}

// ------------------------------------------------------------------ lexing

namespace {

struct Statement {
  std::string text;
  int line = 0;
};

// Splits the text into statements: comments (# or //, outside strings) removed, a
// statement continuing over lines while its parentheses or braces are open.
std::vector<Statement> split_statements(const std::string& text, const std::string& name) {
  std::vector<Statement> out;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  Statement pending;
  int depth = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::string clean;
    bool in_string = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      char c = line[i];
      if (in_string) {
        clean += c;
        if (c == '\\' && i + 1 < line.size()) clean += line[++i];
        else if (c == '"') in_string = false;
        continue;
      }
      if (c == '"') in_string = true;
      if (c == '#' || (c == '/' && i + 1 < line.size() && line[i + 1] == '/')) break;
      if (c == '(' || c == '{') ++depth;
      if (c == ')' || c == '}') --depth;
      clean += c;
    }
    if (in_string) throw TraceError(name, line_no, "unterminated string");
    if (pending.text.empty()) pending.line = line_no;
    if (!pending.text.empty()) pending.text += ' ';
    pending.text += clean;
    if (depth <= 0) {
      if (depth < 0) throw TraceError(name, pending.line, "unbalanced ')' or '}'");
      if (pending.text.find_first_not_of(" \t") != std::string::npos) out.push_back(pending);
      pending = Statement{};
      depth = 0;
    }
  }
  if (!pending.text.empty() && pending.text.find_first_not_of(" \t") != std::string::npos)
    throw TraceError(name, pending.line, "statement not closed: missing ')' or '}' before the end of the file");
  return out;
}

struct Cursor {
  const std::string& s;
  std::size_t pos = 0;
  void skip_ws() {
    while (pos < s.size() && (s[pos] == ' ' || s[pos] == '\t')) ++pos;
  }
  bool at_end() {
    skip_ws();
    return pos >= s.size();
  }
  char peek() {
    skip_ws();
    return pos < s.size() ? s[pos] : '\0';
  }
  bool eat(char c) {
    if (peek() == c) {
      ++pos;
      return true;
    }
    return false;
  }
  std::string identifier() {
    skip_ws();
    std::size_t start = pos;
    while (pos < s.size() && (std::isalnum(static_cast<unsigned char>(s[pos])) || s[pos] == '_')) ++pos;
    return s.substr(start, pos - start);
  }
  // A number-like or name-like token: letters, digits, sign, '.', '+', '-' (exponents), 'x'.
  std::string word() {
    skip_ws();
    std::size_t start = pos;
    while (pos < s.size()) {
      char c = s[pos];
      if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' || c == '-') ++pos;
      else break;
    }
    return s.substr(start, pos - start);
  }
  std::string string_literal() {
    // precondition: peek() == '"'
    ++pos;
    std::string out;
    while (pos < s.size() && s[pos] != '"') {
      char c = s[pos++];
      if (c == '\\' && pos < s.size()) {
        char e = s[pos++];
        if (e == 'n') out += '\n';
        else if (e == 't') out += '\t';
        else if (e == 'x') {
          // \xHH: exactly two hex digits; anything else is a malformed string (std::runtime_error,
          // given the trace's location by the replayer).
          auto hex = [&](std::size_t at) -> int {
            if (at >= s.size()) return -1;
            const char h = s[at];
            return h >= '0' && h <= '9' ? h - '0' : h >= 'a' && h <= 'f' ? h - 'a' + 10 : h >= 'A' && h <= 'F' ? h - 'A' + 10 : -1;
          };
          const int hi = hex(pos), lo = hex(pos + 1);
          if (hi < 0 || lo < 0) throw std::runtime_error("a \\x escape takes two hex digits, e.g. \\x0a");
          out += static_cast<char>(hi * 16 + lo);
          pos += 2;
        } else if (e == '"' || e == '\\') {
          out += e;
        } else {
          // docs/trace-format.md names the escapes; any other is a malformed string, not a
          // character silently dropped or kept.
          throw std::runtime_error(fmt::format("unknown escape '\\{}' in a string (the escapes are \\\" \\\\ \\n \\t \\xHH)",
                                               std::isprint(static_cast<unsigned char>(e)) ? std::string(1, e)
                                                                                           : fmt::format("x{:02x}", static_cast<unsigned char>(e))));
        }
      } else {
        out += c;
      }
    }
    ++pos;  // closing quote
    return out;
  }
};

// A parsed argument before its parameter kind gives it meaning.
struct Arg {
  enum Kind { Expr, String, Array, File, Null } kind = Expr;
  std::vector<std::string> terms;  // Expr: terms joined by '|'
  std::string text;                // String / File
  // Array: its elements' text inside the braces, read when the element type is known. Not a
  // string an element: 16 Mi elements in 32 MiB of trace took 1.3 GB so (hostile-input suite).
  std::string_view elements;
  std::size_t count = 0;
};

// The next element of an array's text (a word: letters, digits, '_', '.', '+', '-'), after the
// separators before it; the text was checked as words and commas when it was parsed.
std::string_view next_element(std::string_view& rest) {
  auto word_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '+' || c == '-';
  };
  std::size_t k = 0;
  while (k < rest.size() && !word_char(rest[k])) ++k;
  std::size_t end = k;
  while (end < rest.size() && word_char(rest[end])) ++end;
  const std::string_view element = rest.substr(k, end - k);
  rest.remove_prefix(end);
  return element;
}

Arg parse_arg(Cursor& c, const std::function<void(const std::string&)>& fail) {
  // "name = value" (apitrace dump style): drop the name.
  {
    std::size_t save = c.pos;
    std::string id = c.identifier();
    c.skip_ws();
    if (!id.empty() && c.pos < c.s.size() && c.s[c.pos] == '=' && (c.pos + 1 >= c.s.size() || c.s[c.pos + 1] != '='))
      ++c.pos;
    else
      c.pos = save;
  }
  Arg a;
  char p = c.peek();
  if (p == '"') {
    a.kind = Arg::String;
    a.text = c.string_literal();
    return a;
  }
  if (p == '{') {
    ++c.pos;
    a.kind = Arg::Array;
    const std::size_t start = c.pos;
    if (c.eat('}')) return a;
    while (true) {
      if (c.word().empty()) fail("expected a number in the array");
      ++a.count;
      if (c.eat('}')) break;
      if (!c.eat(',')) fail("expected ',' or '}' in the array");
      if (c.eat('}')) break;  // trailing comma
    }
    a.elements = std::string_view(c.s).substr(start, c.pos - start);
    return a;
  }
  std::string w = c.word();
  if (w == "file" && c.peek() == '(') {
    ++c.pos;
    if (c.peek() != '"') fail("file(...) takes a quoted path");
    a.kind = Arg::File;
    a.text = c.string_literal();
    if (!c.eat(')')) fail("expected ')' after the file path");
    return a;
  }
  if (w == "NULL" || w == "nullptr") {
    a.kind = Arg::Null;
    return a;
  }
  if (w.empty()) fail("expected an argument");
  a.terms.push_back(w);
  while (c.eat('|')) {
    std::string t = c.word();
    if (t.empty()) fail("expected a term after '|'");
    a.terms.push_back(t);
  }
  return a;
}

template <class T>
std::optional<T> parse_number(std::string_view w) {
  if constexpr (std::is_floating_point_v<T>) {
    std::string_view v = w;
    bool neg = false;
    if (!v.empty() && (v[0] == '-' || v[0] == '+')) {
      neg = v[0] == '-';
      v.remove_prefix(1);
    }
    T out{};
    std::from_chars_result r;
    if (v.size() > 2 && v[0] == '0' && (v[1] == 'x' || v[1] == 'X')) {
      v.remove_prefix(2);
      r = std::from_chars(v.data(), v.data() + v.size(), out, std::chars_format::hex);
    } else {
      r = std::from_chars(v.data(), v.data() + v.size(), out);
    }
    if (r.ec != std::errc() || r.ptr != v.data() + v.size()) return std::nullopt;
    return neg ? -out : out;
  } else {
    std::string_view v = w;
    bool neg = false;
    if (!v.empty() && (v[0] == '-' || v[0] == '+')) {
      neg = v[0] == '-';
      v.remove_prefix(1);
    }
    int base = 10;
    if (v.size() > 2 && v[0] == '0' && (v[1] == 'x' || v[1] == 'X')) {
      v.remove_prefix(2);
      base = 16;
    }
    std::uint64_t out = 0;
    auto r = std::from_chars(v.data(), v.data() + v.size(), out, base);
    if (r.ec != std::errc() || r.ptr != v.data() + v.size() || v.empty()) return std::nullopt;
    if (out > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return std::nullopt;
    const std::int64_t s = neg ? -static_cast<std::int64_t>(out) : static_cast<std::int64_t>(out);
    return static_cast<T>(s);
  }
}

// ------------------------------------------------------------------ replay

class Replayer {
 public:
  Replayer(const std::string& name, const std::filesystem::path& base, const ReplayOptions& options)
      : name_(name), side_files_(base, options.allow_files), options_(options) {}

  ReplayResult run(const std::string& text) {
    std::vector<Statement> statements = split_statements(text, name_);
    bool seen_version = false;
    for (const Statement& st : statements) {
      line_ = st.line;
      Cursor c{st.text};
      if (!seen_version) {
        std::string w = c.word();
        if (w != "passim-trace") fail("the first line of a trace must be 'passim-trace 1'");
        std::string v = c.word();
        auto version = parse_number<std::int64_t>(v);
        if (!version) fail("'passim-trace' takes the format version, e.g. 'passim-trace 1'");
        if (*version != kTraceFormatVersion)
          fail(fmt::format("trace format version {} is not supported (this passim reads version {})", *version,
                           kTraceFormatVersion));
        if (!c.at_end()) fail("unexpected text after the format version");
        seen_version = true;
        continue;
      }
      // Whatever a statement throws is reported at its line (docs/hostile-input.md).
      try {
        if (c.peek() == '@') {
          ++c.pos;
          directive(c);
        } else {
          call(c);
        }
      } catch (const TraceError&) {
        throw;
      } catch (const std::bad_alloc&) {
        fail("out of memory (--max-memory sets the run's budget)");
      } catch (const std::exception& e) {
        fail(e.what());
      }
    }
    if (!seen_version) {
      line_ = 1;
      fail("empty trace: the first line must be 'passim-trace 1'");
    }
    ensure_context();
    result_.context->check_balance();
    return std::move(result_);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { throw TraceError(name_, line_, message); }

  void ensure_context() {
    if (result_.context) return;
    // The context is made at the first call; what its settings get wrong is the header's
    // (the last header directive's line), not that call's.
    const int call_line = line_;
    if (header_line_ > 0) line_ = header_line_;
    TraceSettings& s = result_.settings;
    const MachineProfile* profile = find_profile(profile_name_);
    if (!profile) fail(fmt::format("unknown machine profile '{}' (see 'passim info')", profile_name_));
    s.profile = profile_name_;
    FramebufferConfig f;
    f.color_bits = profile->color_bits;
    f.depth_bits = profile->depth_bits;
    f.stencil_bits = profile->stencil_bits;
    f.accum_bits = profile->accum_bits;
    for (const auto& [key, value] : fb_overrides_) apply_framebuffer_setting(f, key, value);
    if (!fb_overrides_.count("accum") && fb_overrides_.count("color"))
      f.accum_bits = FramebufferConfig::default_accum_bits(f.color_bits);
    if (options_.window_limit > 0) {
      f.width = std::min(f.width, options_.window_limit);
      f.height = std::min(f.height, options_.window_limit);
    }
    s.framebuffer = f;
    s.subpixel_bits = subpixel_;
    MachineProfile m = s.machine();
    if (m.limits.subpixel_bits < 0 || m.limits.subpixel_bits > 12) fail("@subpixel takes 0..12");
    std::string err = f.validate(m.limits.max_framebuffer_size);
    if (!err.empty()) fail(err);
    try {
      result_.context = std::make_unique<Context>(f, m, options_.max_memory);
    } catch (const BudgetExceeded& e) {
      fail(e.what());
    }
    line_ = call_line;
    result_.context->set_pass_end_observer(options_.pass_end);
    runner_ = std::make_unique<CallRunner>(*result_.context, options_.strict, options_.diagnostics);
    runner_->set_query_log(options_.queries);
    if (options_.record) {
      options_.record->write_header(s);
      result_.context->set_call_sink(options_.record);
    }
  }

  void apply_framebuffer_setting(FramebufferConfig& f, const std::string& key, const std::string& value) {
    auto integer = [&](const std::string& v) {
      auto n = parse_number<std::int64_t>(v);
      if (!n || *n < 0 || *n > 1000000)
        fail(fmt::format("@framebuffer {}={}: expected a whole number from 0 to 1000000", key, v));
      return static_cast<int>(*n);
    };
    if (key == "size") {
      std::size_t x = value.find('x');
      if (x == std::string::npos) fail("@framebuffer size must be WIDTHxHEIGHT, e.g. 800x600");
      f.width = integer(value.substr(0, x));
      f.height = integer(value.substr(x + 1));
    } else if (key == "color") {
      std::vector<int> bits;
      std::stringstream ss(value);
      std::string part;
      while (std::getline(ss, part, ',')) bits.push_back(integer(part));
      if (bits.size() == 1) f.color_bits = {bits[0], bits[0], bits[0], bits[0]};
      else if (bits.size() == 4) f.color_bits = {bits[0], bits[1], bits[2], bits[3]};
      else if (bits.size() == 3) f.color_bits = {bits[0], bits[1], bits[2], 0};
      else fail("@framebuffer color= takes one width, R,G,B or R,G,B,A");
    } else if (key == "depth") {
      f.depth_bits = integer(value);
    } else if (key == "stencil") {
      f.stencil_bits = integer(value);
    } else if (key == "accum") {
      f.accum_bits = integer(value);
    } else if (key == "double") {
      if (value != "yes" && value != "no") fail("@framebuffer double= takes yes or no");
      f.double_buffer = value == "yes";
    } else {
      fail(fmt::format("unknown @framebuffer setting '{}' (size, color, depth, stencil, accum, double)", key));
    }
  }

  void directive(Cursor& c) {
    const std::string d = c.identifier();
    auto rest_words = [&] {
      std::vector<std::string> words;
      while (!c.at_end()) {
        if (c.peek() == '"') {
          words.push_back(c.string_literal());
          continue;
        }
        std::size_t start = c.pos;
        while (c.pos < c.s.size() && c.s[c.pos] != ' ' && c.s[c.pos] != '\t') ++c.pos;
        words.push_back(c.s.substr(start, c.pos - start));
      }
      return words;
    };
    const bool header = d == "profile" || d == "framebuffer" || d == "subpixel";
    if (header) header_line_ = line_;
    if (header && result_.context) fail(fmt::format("@{} must come before the first GL call", d));
    std::vector<std::string> w = rest_words();
    if (d == "profile") {
      if (w.size() != 1) fail("@profile takes one name (see 'passim info')");
      if (!find_profile(w[0])) fail(fmt::format("unknown machine profile '{}' (see 'passim info')", w[0]));
      profile_name_ = w[0];
    } else if (d == "framebuffer") {
      for (const std::string& item : w) {
        std::size_t eq = item.find('=');
        if (eq == std::string::npos) fb_overrides_["size"] = item;
        else fb_overrides_[item.substr(0, eq)] = item.substr(eq + 1);
      }
      FramebufferConfig probe;
      for (const auto& [k, v] : fb_overrides_) apply_framebuffer_setting(probe, k, v);
    } else if (d == "subpixel") {
      if (w.size() != 1) fail("@subpixel takes one number of bits");
      auto n = parse_number<std::int64_t>(w[0]);
      if (!n || *n < 0 || *n > 12) fail("@subpixel takes 0..12");
      subpixel_ = static_cast<int>(*n);
    } else if (d == "output") {
      ensure_context();
      output(w);
    } else if (d == "swap") {
      ensure_context();
      if (!w.empty()) fail("@swap takes no arguments");
      result_.context->swap_buffers();
      if (options_.record) options_.record->swap();
    } else if (d == "mesh") {
      ensure_context();
      if (w.size() != 1) fail("@mesh takes one OBJ file name");
      mesh(w[0]);
    } else {
      fail(fmt::format("unknown directive '@{}' (profile, framebuffer, subpixel, output, swap, mesh)", d));
    }
  }

  // @output NAME [PLANE] [BUFFER] [X Y W H]
  void output(std::vector<std::string> w) {
    CaptureRegion region;
    if (w.size() >= 5) {
      int v[4];
      for (int k = 0; k < 4; ++k) {
        const std::string& t = w[w.size() - 4 + static_cast<std::size_t>(k)];
        char* end = nullptr;
        const long x = std::strtol(t.c_str(), &end, 10);
        if (t.empty() || *end != '\0' || x < 0 || x > (1L << 20)) fail(fmt::format("@output region value '{}' is not a size", t));
        v[k] = static_cast<int>(x);
      }
      region = {v[0], v[1], v[2], v[3]};
      w.resize(w.size() - 4);
      const FramebufferConfig& c = result_.context->config();
      if (region.width == 0 || region.height == 0 || region.x + region.width > c.width ||
          region.y + region.height > c.height)
        fail(fmt::format("@output region {} {} {} {} is empty or leaves the {}x{} framebuffer", region.x, region.y,
                         region.width, region.height, c.width, c.height));
    }
    if (w.empty() || w.size() > 3) fail("@output takes NAME [color|rgb|alpha|depth|stencil] [buffer] [x y width height]");
    const std::string& name = w[0];
    for (char ch : name)
      if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-' && ch != '.')
        fail(fmt::format("@output name '{}' may hold only letters, digits, '_', '-' and '.'", name));
    for (const CapturedImage& img : result_.images)
      if (img.name == name) fail(fmt::format("@output '{}' is already used in this trace", name));
    std::string plane = w.size() >= 2 ? w[1] : "color";
    if (plane != "color" && plane != "rgb" && plane != "alpha" && plane != "depth" && plane != "stencil")
      fail(fmt::format("@output plane '{}' is not color, rgb, alpha, depth or stencil", plane));
    Context& ctx = *result_.context;
    GLenum buffer = ctx.read_buffer();
    if (w.size() == 3) {
      auto v = enum_value(w[2]);
      if (!v) fail(fmt::format("unknown buffer '{}'", w[2]));
      buffer = *v;
    }
    const bool color = plane == "color" || plane == "rgb" || plane == "alpha";
    if (color && !ctx.color_buffer(buffer))
      fail(fmt::format("@output {}: the framebuffer has no buffer {}", name, w.size() == 3 ? w[2] : "to read"));
    if (plane == "alpha" && ctx.config().color_bits[3] == 0) fail("@output alpha: the framebuffer has no alpha plane");
    if (plane == "depth" && ctx.config().depth_bits == 0) fail("@output depth: the framebuffer has no depth plane");
    if (plane == "stencil" && ctx.config().stencil_bits == 0)
      fail("@output stencil: the framebuffer has no stencil plane");
    result_.images.push_back(capture_plane(ctx, name, plane, buffer, region));
    if (options_.record) options_.record->output(name, plane, color ? enum_name(buffer, EnumRole::Buffer) : "", region);
  }

  void mesh(const std::string& file) {
    std::vector<ObjShape> shapes;
    try {
      shapes = read_obj(side_files_, file, side_file_limit());
    } catch (const std::runtime_error& e) {  // ObjError, SideFileRefused
      fail(fmt::format("@mesh: {}", e.what()));
    }
    Context& ctx = *result_.context;
    ctx.set_source_location(fmt::format("{}:{}", name_, line_));
    ctx.glBegin(GL_TRIANGLES);
    for (const ObjShape& shape : shapes) {
      for (const ObjCorner& c : shape.corners) {
        if (c.normal) ctx.glNormal3f((*c.normal)[0], (*c.normal)[1], (*c.normal)[2]);
        ctx.glVertex3f(c.position[0], c.position[1], c.position[2]);
      }
    }
    ctx.glEnd();
    report_errors();
  }

  Value convert(const Arg& a, const CallInfo::Param& p, const CallInfo& info, std::size_t index,
                const std::vector<Value>& done) {
    Value v;
    auto need_expr = [&] {
      if (a.kind != Arg::Expr)
        fail(fmt::format("{}: argument {} must be a {}", info.name, index + 1, "number or enum"));
    };
    auto enum_term = [&](const std::string& t) -> std::int64_t {
      if (t.rfind("GL_", 0) == 0) {
        auto e = enum_value(t);
        if (!e) fail(fmt::format("{}: unknown enum '{}'", info.name, t));
        return *e;
      }
      auto n = parse_number<std::int64_t>(t);
      if (!n) fail(fmt::format("{}: argument {}: '{}' is not an enum or a whole number", info.name, index + 1, t));
      return *n;
    };
    switch (p.kind) {
      case 'e': case 'm': case 'n': case 'b': case 'k': case 'x': {
        need_expr();
        std::int64_t acc = 0;
        for (const std::string& t : a.terms) acc |= enum_term(t);
        if (acc < std::numeric_limits<std::int32_t>::min() || acc > std::numeric_limits<std::uint32_t>::max())
          fail(fmt::format("{}: argument {} is out of range", info.name, index + 1));
        v.i = acc;
        return v;
      }
      case 'z': {
        need_expr();
        const std::string& t = a.terms[0];
        if (t == "GL_TRUE" || t == "true" || t == "1") v.i = 1;
        else if (t == "GL_FALSE" || t == "false" || t == "0") v.i = 0;
        else fail(fmt::format("{}: argument {} must be GL_TRUE or GL_FALSE, not '{}'", info.name, index + 1, t));
        return v;
      }
      case 'i': case 'u': case 'c': case 'g': case 'h': case 'w': {
        need_expr();
        if (a.terms.size() != 1) fail(fmt::format("{}: argument {} must be a whole number", info.name, index + 1));
        auto n = parse_number<std::int64_t>(a.terms[0]);
        if (!n) fail(fmt::format("{}: argument {}: '{}' is not a whole number", info.name, index + 1, a.terms[0]));
        const IntegerRange range = integer_range(p.kind);
        const bool ok = *n >= range.lo && *n <= range.hi;
        if (!ok) fail(fmt::format("{}: argument {} ({}) is out of range", info.name, index + 1, *n));
        v.i = *n;
        return v;
      }
      case 'f': case 'y': case 'd': {
        need_expr();
        if (a.terms.size() != 1) fail(fmt::format("{}: argument {} must be a number", info.name, index + 1));
        const std::string& t = a.terms[0];
        if (p.kind == 'y' && t.rfind("GL_", 0) == 0) {
          v.d = static_cast<double>(enum_term(t));
          return v;
        }
        if (p.kind == 'd') {
          auto d = parse_number<double>(t);
          if (!d) fail(fmt::format("{}: argument {}: '{}' is not a number", info.name, index + 1, t));
          v.d = *d;
        } else {
          auto f = parse_number<float>(t);
          if (!f) fail(fmt::format("{}: argument {}: '{}' is not a number", info.name, index + 1, t));
          v.d = *f;
        }
        return v;
      }
      case 's':
        if (a.kind != Arg::String) fail(fmt::format("{}: argument {} must be a quoted string", info.name, index + 1));
        v.set_str(a.text);
        return v;
      case 'O':
        return v;
      default:
        break;
    }
    // Arrays.
    const GLenum type = param_element_type(info, index, done);
    const int size = type_size(type);
    if (size == 0) fail(fmt::format("{}: unknown data type {} for argument {}", info.name, enum_name(type), index + 1));
    v.elem_type = type;
    auto bytes = std::make_shared<std::vector<std::byte>>();
    if (a.kind == Arg::Null) {
      v.count = 0;
    } else if (a.kind == Arg::File) {
      std::string raw;
      try {
        raw = side_files_.read(a.text, side_file_limit());
      } catch (const SideFileRefused& e) {
        fail(e.what());
      }
      if (raw.size() % static_cast<std::size_t>(size) != 0)
        fail(fmt::format("side file '{}' holds {} bytes, not a whole number of {}-byte elements", a.text, raw.size(),
                         size));
      bytes->resize(raw.size());
      // An empty file (or a /proc file, which states a size of 0) leaves data() null, which
      // memcpy may not be given even for 0 bytes (UBSan, hostile case proc_self_allowed).
      if (!raw.empty()) std::memcpy(bytes->data(), raw.data(), raw.size());
      v.count = raw.size() / static_cast<std::size_t>(size);
    } else if (a.kind == Arg::Array) {
      bytes->resize(a.count * static_cast<std::size_t>(size));
      std::string_view rest = a.elements;
      for (std::size_t k = 0; k < a.count; ++k) {
        std::byte* dst = bytes->data() + k * static_cast<std::size_t>(size);
        const std::string_view t = next_element(rest);
        auto bad = [&] { fail(fmt::format("{}: array element {} '{}' is not a valid {}", info.name, k + 1, t, enum_name(type))); };
        auto store_int = [&](auto tag, std::int64_t lo, std::int64_t hi) {
          auto n = parse_number<std::int64_t>(t);
          if (!n || *n < lo || *n > hi) bad();
          decltype(tag) x = static_cast<decltype(tag)>(*n);
          std::memcpy(dst, &x, sizeof(x));
        };
        switch (type) {
          case GL_FLOAT: { auto f = parse_number<float>(t); if (!f) bad(); std::memcpy(dst, &*f, 4); break; }
          case GL_DOUBLE: { auto d = parse_number<double>(t); if (!d) bad(); std::memcpy(dst, &*d, 8); break; }
          case GL_INT: store_int(std::int32_t{}, INT32_MIN, INT32_MAX); break;
          case GL_UNSIGNED_INT: store_int(std::uint32_t{}, 0, UINT32_MAX); break;
          case GL_SHORT: store_int(std::int16_t{}, INT16_MIN, INT16_MAX); break;
          case GL_UNSIGNED_SHORT: store_int(std::uint16_t{}, 0, UINT16_MAX); break;
          case GL_BYTE: store_int(std::int8_t{}, INT8_MIN, INT8_MAX); break;
          default: store_int(std::uint8_t{}, 0, UINT8_MAX); break;
        }
      }
      v.count = a.count;
    } else {
      fail(fmt::format("{}: argument {} must be an array {{...}}, file(\"...\") or NULL", info.name, index + 1));
    }
    v.bytes = std::move(bytes);
    return v;  // its length is checked against the call's row when it runs (CallRunner)
  }

  void call(Cursor& c) {
    // An optional leading call number (apitrace dump).
    if (std::isdigit(static_cast<unsigned char>(c.peek()))) c.word();
    const std::string fn = c.identifier();
    if (fn.empty()) fail(fmt::format("expected a GL call, found '{}'", c.s.substr(c.pos, 40)));
    const CallInfo* info = find_call(fn);
    if (!info) fail(fmt::format("unknown call '{}' (see docs/trace-format.md for the calls passim knows)", fn));
    if (!c.eat('(')) fail(fmt::format("expected '(' after {}", fn));
    std::vector<Arg> args;
    auto failer = [&](const std::string& m) { fail(fmt::format("{}: {}", fn, m)); };
    if (!c.eat(')')) {
      while (true) {
        args.push_back(parse_arg(c, failer));
        if (c.eat(')')) break;
        if (!c.eat(',')) fail(fmt::format("{}: expected ',' or ')' after argument {}", fn, args.size()));
      }
    }
    if (c.eat('=')) c.pos = c.s.size();  // a recorded return value: ignored
    if (!c.at_end()) fail(fmt::format("unexpected text after {}(...)", fn));
    if (args.size() != info->params.size())
      fail(fmt::format("{} takes {} arguments, the trace gives {}", fn, info->params.size(), args.size()));
    std::vector<Value> values;
    for (std::size_t k = 0; k < args.size(); ++k) values.push_back(convert(args[k], info->params[k], *info, k, values));
    ensure_context();
    try {
      runner_->run(*info, values, fmt::format("{}:{}", name_, line_));
    } catch (const CallRejected& e) {
      fail(e.what());
    }
  }

  void report_errors() {
    try {
      runner_->report_errors();
    } catch (const CallRejected& e) {
      fail(e.what());
    }
  }

  // What a side file may take: what is left of the run's budget.
  std::uint64_t side_file_limit() const {
    return result_.context ? result_.context->memory().left() : options_.max_memory;
  }

  std::string name_;
  SideFiles side_files_;
  ReplayOptions options_;
  int line_ = 0;
  int header_line_ = 0;  // the last @profile, @framebuffer or @subpixel
  std::string profile_name_ = "ideal";
  std::map<std::string, std::string> fb_overrides_;
  int subpixel_ = -1;
  ReplayResult result_;
  std::unique_ptr<CallRunner> runner_;
};

}  // namespace

ReplayResult replay_trace_text(const std::string& text, const std::string& name, const std::filesystem::path& base,
                               const ReplayOptions& options) {
  Replayer r(name, base, options);
  return r.run(text);
}

ReplayResult replay_trace(const std::filesystem::path& file, const ReplayOptions& options) {
  // The trace itself: a regular file, read whole, and no larger than the run's budget.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw TraceError(file.string(), 0,
                     std::filesystem::exists(file, ec) ? "not a regular file" : "cannot open the trace file");
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) throw TraceError(file.string(), 0, "cannot open the trace file");
  if (size > options.max_memory)
    throw TraceError(file.string(), 0,
                     fmt::format("the trace is {} bytes, more than the run's memory budget of {} (--max-memory)",
                                 size, options.max_memory));
  std::ifstream in(file, std::ios::binary);
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!in || !in.read(text.data(), static_cast<std::streamsize>(size)))
    throw TraceError(file.string(), 0, "cannot read the trace file");
  return replay_trace_text(text, file.string(), file.parent_path(), options);
}

std::string skipped_lines(const std::vector<SkippedCall>& skipped) {
  std::string text;
  for (const SkippedCall& s : skipped)
    text += fmt::format("passim: skipped {} call{} of {} ({})\n", s.count, s.count == 1 ? "" : "s", s.name, s.why);
  return text;
}

// ------------------------------------------------------------------ writing

void TraceWriter::write_header(const TraceSettings& settings) {
  out_ << "passim-trace " << kTraceFormatVersion << "\n";
  for (const std::string& line : settings.header_lines()) out_ << line << "\n";
}

void TraceWriter::on_call(const Call& call) { out_ << format_call(call) << "\n"; }

void TraceWriter::output(const std::string& name, const std::string& plane, const std::string& buffer,
                         CaptureRegion region) {
  out_ << "@output " << name << " " << plane;
  if (plane == "color" || plane == "rgb" || plane == "alpha") out_ << " " << buffer;
  if (region.width != 0) out_ << " " << region.x << " " << region.y << " " << region.width << " " << region.height;
  out_ << "\n";
}

void TraceWriter::swap() { out_ << "@swap\n"; }

}  // namespace passim
