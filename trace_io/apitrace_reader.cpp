#include "trace_io/apitrace_reader.hpp"

#include <fmt/format.h>
#include <snappy.h>

#include <cstring>
#include <limits>

namespace passim::apitrace {

namespace {
// FORMAT.markdown "Calls" and "Values": the tags of the stream.
enum : std::uint8_t { kEventEnter = 0, kEventLeave = 1 };
enum : std::uint8_t { kCallEnd = 0, kCallArg, kCallRet, kCallThread, kCallBacktrace, kCallFlags };
enum : std::uint8_t { kFrameEnd = 0, kFrameModule, kFrameFunction, kFrameFile, kFrameLine, kFrameOffset };
constexpr std::uint64_t kFlagFake = 1;
// apitrace's writer compresses at most 1 MiB per chunk; a chunk claiming far more is corrupt.
constexpr std::size_t kMaxChunk = 64u << 20;
// Nesting of arrays and structures in one value; GL's deepest is two.
constexpr int kMaxDepth = 32;
// Arguments of one function; GL's longest takes 11.
constexpr std::uint64_t kMaxArgs = 256;
}  // namespace

FormatError::FormatError(long long c, const std::string& message)
    : std::runtime_error(c >= 0 ? fmt::format("call {}: {}", c, message) : message), call(c) {}

namespace {
// Where the stream stopped, for messages: snappy chunks decompress whole, so a file cut
// inside its first chunk stops before any call.
std::string before_first_call(const std::string& message) { return "before the first call: " + message; }
}  // namespace

bool Value::is_integer() const {
  switch (kind) {
    case Kind::SInt: case Kind::UInt: case Kind::Enum: case Kind::Bitmask: case Kind::False: case Kind::True:
      return true;
    case Kind::Repr:
      return items.size() == 2 && items[1].is_integer();
    default:
      return false;
  }
}

std::int64_t Value::as_integer() const {
  switch (kind) {
    case Kind::UInt: case Kind::Bitmask: return static_cast<std::int64_t>(u);
    case Kind::Repr: return items[1].as_integer();
    default: return i;
  }
}

double Value::as_double() const {
  if (kind == Kind::Float || kind == Kind::Double) return d;
  if (kind == Kind::UInt || kind == Kind::Bitmask) return static_cast<double>(u);
  if (kind == Kind::Repr && items.size() == 2) return items[1].as_double();
  return static_cast<double>(i);
}

Reader::Reader(std::istream& in, std::uint64_t max_held_bytes) : in_(in), max_held_(max_held_bytes) {
  char magic[2] = {0, 0};
  in_.read(magic, 2);
  if (in_.gcount() != 2) fail("not an apitrace trace: the file is shorter than its 2-byte header");
  if (static_cast<unsigned char>(magic[0]) == 0x1f && static_cast<unsigned char>(magic[1]) == 0x8b)
    fail("a gzip-compressed apitrace trace: passim reads snappy-compressed traces; convert with "
         "'apitrace repack' from a current apitrace");
  if (magic[0] != 'a' || magic[1] != 't')
    fail("not an apitrace trace: it does not start with the snappy stream header 'at'");
  magic_read_ = true;
  const std::uint64_t v = uint();
  if (v < kOldestVersion || v > kNewestVersion)
    fail(fmt::format("apitrace format version {} is not supported (passim reads versions {} to {})", v,
                     kOldestVersion, kNewestVersion));
  version_ = static_cast<unsigned>(v);
  if (version_ >= 6) {
    uint();  // semantic version: which retrace semantics apply; passim's are version 6's
    while (true) {
      std::string name = string(Held::Signature);
      if (name.empty()) break;
      properties_[name] = string(Held::Signature);
    }
  }
}

Reader::~Reader() = default;

void Reader::fail(const std::string& message) const {
  if (current_call_ < 0 && magic_read_) throw FormatError(current_call_, before_first_call(message));
  throw FormatError(current_call_, message);
}

bool Reader::fill() {
  if (eof_) return false;
  unsigned char len_bytes[4];
  in_.read(reinterpret_cast<char*>(len_bytes), 4);
  if (in_.gcount() == 0) {
    eof_ = true;
    return false;
  }
  if (in_.gcount() != 4) fail("truncated: the file ends inside a chunk header");
  const std::size_t length = static_cast<std::size_t>(len_bytes[0]) | static_cast<std::size_t>(len_bytes[1]) << 8 |
                             static_cast<std::size_t>(len_bytes[2]) << 16 |
                             static_cast<std::size_t>(len_bytes[3]) << 24;
  if (length > kMaxChunk) fail(fmt::format("corrupt: a chunk claims {} compressed bytes", length));
  std::string compressed(length, '\0');
  in_.read(compressed.data(), static_cast<std::streamsize>(length));
  if (static_cast<std::size_t>(in_.gcount()) != length) fail("truncated: the file ends inside a compressed chunk");
  std::size_t size = 0;
  if (!snappy::GetUncompressedLength(compressed.data(), length, &size) || size > kMaxChunk)
    fail("corrupt: a chunk is not valid snappy data");
  chunk_.clear();
  if (!snappy::Uncompress(compressed.data(), length, &chunk_)) fail("corrupt: a chunk is not valid snappy data");
  pos_ = 0;
  return true;
}

std::uint8_t Reader::byte() {
  while (pos_ >= chunk_.size())
    if (!fill()) fail("truncated: the trace ends in the middle of a call");
  return static_cast<std::uint8_t>(chunk_[pos_++]);
}

// FORMAT.markdown "Basic types": 7 bits per byte, least significant first.
std::uint64_t Reader::uint() {
  std::uint64_t value = 0;
  for (int shift = 0;; shift += 7) {
    const std::uint8_t b = byte();
    if (shift > 63 || (shift == 63 && (b & 0x7e))) fail("corrupt: a variable-length integer exceeds 64 bits");
    value |= static_cast<std::uint64_t>(b & 0x7f) << shift;
    if (!(b & 0x80)) return value;
  }
}

void Reader::hold(std::uint64_t bytes, Held held) {
  if (bytes > max_held_ - held_)
    fail(fmt::format("too large: its values need more than the {} bytes the reader may hold (--max-memory / 4; "
                     "corrupt, or compressed data that expands enormously)",
                     max_held_));
  held_ += bytes;
  if (held == Held::Call) call_bytes_ += bytes;
}

std::string Reader::string(Held held) {
  const std::uint64_t length = uint();
  std::string s;
  // Copied a chunk at a time, so a corrupt length costs only the bytes really present, and
  // held as it grows.
  while (s.size() < length) {
    if (pos_ >= chunk_.size() && !fill()) fail("truncated: the trace ends inside a string or blob");
    const std::size_t take = static_cast<std::size_t>(std::min<std::uint64_t>(length - s.size(), chunk_.size() - pos_));
    hold(take, held);
    s.append(chunk_, pos_, take);
    pos_ += take;
  }
  return s;
}

float Reader::read_float() {
  unsigned char b[4];
  for (auto& c : b) c = byte();
  std::uint32_t bits = static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
                       static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

double Reader::read_double() {
  std::uint64_t bits = 0;
  for (int k = 0; k < 8; ++k) bits |= static_cast<std::uint64_t>(byte()) << (8 * k);
  double d;
  std::memcpy(&d, &bits, 8);
  return d;
}

Value Reader::value(int depth) {
  if (depth > kMaxDepth) fail("corrupt: values nested too deeply");
  // A value in an array or structure costs its own size twice (the vector's spare capacity).
  hold(2 * sizeof(Value), Held::Call);
  Value v;
  const std::uint8_t tag = byte();
  switch (tag) {
    case 0x00: v.kind = Value::Kind::Null; break;
    case 0x01: v.kind = Value::Kind::False; v.i = 0; break;
    case 0x02: v.kind = Value::Kind::True; v.i = 1; break;
    case 0x03: {
      v.kind = Value::Kind::SInt;
      const std::uint64_t m = uint();
      // -m, with m = 2^63 giving INT64_MIN and larger magnitudes rejected.
      if (m > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()) + 1)
        fail("corrupt: a negative integer below -2^63");
      v.i = m == 0 ? 0 : -static_cast<std::int64_t>(m - 1) - 1;
      break;
    }
    case 0x04: v.kind = Value::Kind::UInt; v.u = uint(); v.i = static_cast<std::int64_t>(v.u); break;
    case 0x05: v.kind = Value::Kind::Float; v.d = static_cast<double>(read_float()); break;
    case 0x06: v.kind = Value::Kind::Double; v.d = read_double(); break;
    case 0x07: v.kind = Value::Kind::String; v.bytes = string(Held::Call); break;
    case 0x08: v.kind = Value::Kind::Blob; v.bytes = string(Held::Call); break;
    case 0x09: {
      v.kind = Value::Kind::Enum;
      if (version_ < 3) {  // the name, then the value
        v.bytes = string(Held::Call);
        v.i = value(depth + 1).as_integer();
        break;
      }
      const std::uint64_t id = uint();
      auto it = enums_.find(id);
      if (it == enums_.end()) {
        std::vector<std::pair<std::string, std::int64_t>> names;
        const std::uint64_t n = uint();
        for (std::uint64_t k = 0; k < n; ++k) {
          std::string name = string(Held::Signature);
          hold(sizeof(std::pair<std::string, std::int64_t>), Held::Signature);
          const Value x = value(depth + 1);
          if (!x.is_integer()) fail("corrupt: an enum signature value is not an integer");
          names.emplace_back(std::move(name), x.as_integer());
        }
        it = enums_.emplace(id, std::move(names)).first;
      }
      const Value x = value(depth + 1);
      if (!x.is_integer()) fail("corrupt: an enum value is not an integer");
      v.i = x.as_integer();
      for (const auto& [name, number] : it->second)
        if (number == v.i) {
          v.bytes = name;
          break;
        }
      break;
    }
    case 0x0a: {
      v.kind = Value::Kind::Bitmask;
      const std::uint64_t id = uint();
      if (!bitmasks_.count(id)) {
        const std::uint64_t n = uint();
        for (std::uint64_t k = 0; k < n; ++k) {
          string(Held::Call);  // read past: passim keeps the numbers only
          uint();
        }
        hold(64, Held::Signature);
        bitmasks_[id] = true;
      }
      v.u = uint();
      v.i = static_cast<std::int64_t>(v.u);
      break;
    }
    case 0x0b: {
      v.kind = Value::Kind::Array;
      const std::uint64_t n = uint();
      for (std::uint64_t k = 0; k < n; ++k) v.items.push_back(value(depth + 1));  // each needs >= 1 byte
      break;
    }
    case 0x0c: {
      v.kind = Value::Kind::Struct;
      const std::uint64_t id = uint();
      auto it = structs_.find(id);
      if (it == structs_.end()) {
        string(Held::Call);  // struct name
        const std::uint64_t n = uint();
        if (n > kMaxArgs) fail("corrupt: a structure with too many members");
        for (std::uint64_t k = 0; k < n; ++k) string(Held::Call);
        hold(64, Held::Signature);
        it = structs_.emplace(id, static_cast<std::size_t>(n)).first;
      }
      for (std::size_t k = 0; k < it->second; ++k) v.items.push_back(value(depth + 1));
      break;
    }
    case 0x0d: v.kind = Value::Kind::Pointer; v.u = uint(); break;
    case 0x0e: {
      v.kind = Value::Kind::Repr;
      v.items.push_back(value(depth + 1));
      v.items.push_back(value(depth + 1));
      break;
    }
    case 0x0f: {
      v.kind = Value::Kind::WString;
      const std::uint64_t n = uint();
      for (std::uint64_t k = 0; k < n; ++k) {
        const std::uint64_t c = uint();
        hold(1, Held::Call);
        v.bytes.push_back(c < 0x80 ? static_cast<char>(c) : '?');
      }
      break;
    }
    default:
      fail(fmt::format("corrupt: unknown value type 0x{:02x}", tag));
  }
  return v;
}

std::shared_ptr<const FunctionSig> Reader::function_sig() {
  const std::uint64_t id = uint();
  auto it = functions_.find(id);
  if (it != functions_.end()) return it->second;
  auto sig = std::make_shared<FunctionSig>();
  hold(sizeof(FunctionSig) + 64, Held::Signature);
  sig->name = string(Held::Signature);
  const std::uint64_t n = uint();
  if (n > kMaxArgs) fail(fmt::format("corrupt: function '{}' declares {} arguments", sig->name, n));
  for (std::uint64_t k = 0; k < n; ++k) sig->arg_names.push_back(string(Held::Signature));
  functions_.emplace(id, sig);
  return sig;
}

void Reader::call_details(Call& call, bool leave) {
  while (true) {
    const std::uint8_t tag = byte();
    switch (tag) {
      case kCallEnd:
        return;
      case kCallArg: {
        const std::uint64_t index = uint();
        if (index >= call.args.size())
          fail(fmt::format("{} has {} arguments, the trace gives argument {}", call.name(), call.args.size(),
                           index + 1));
        call.args[index] = value();
        break;
      }
      case kCallRet:
        call.ret = value();
        break;
      case kCallThread:
        call.thread = uint();
        break;
      case kCallBacktrace: {
        const std::uint64_t frames = uint();
        for (std::uint64_t k = 0; k < frames; ++k) {
          const std::uint64_t id = uint();
          if (frames_.count(id)) continue;
          hold(64, Held::Signature);
          frames_[id] = true;
          for (std::uint8_t d = byte(); d != kFrameEnd; d = byte()) {
            if (d == kFrameLine || d == kFrameOffset) uint();
            else if (d >= kFrameModule && d <= kFrameFile) string(Held::Call);
            else fail(fmt::format("corrupt: unknown backtrace detail 0x{:02x}", d));
          }
        }
        break;
      }
      case kCallFlags:
        call.fake = (uint() & kFlagFake) != 0;
        break;
      default:
        fail(fmt::format("corrupt: unknown call detail 0x{:02x}{}", tag, leave ? " in a leave event" : ""));
    }
  }
}

std::optional<Call> Reader::next() {
  while (true) {
    bool more = true;
    while (more && pos_ >= chunk_.size()) more = fill();
    if (!more) {
      if (pending_.empty()) return std::nullopt;
      // Calls that never returned (the program exited inside them, or the trace was cut).
      auto it = pending_.begin();
      Call call = std::move(it->second.first);
      held_ -= it->second.second;
      pending_.erase(it);
      call.incomplete = true;
      return call;
    }
    const std::uint8_t event = byte();
    if (event == kEventEnter) {
      Call call;
      call.number = next_call_++;
      current_call_ = static_cast<long long>(call.number);
      call_bytes_ = 0;
      hold(sizeof(Call) + 64, Held::Call);
      if (version_ >= 4) call.thread = uint();
      call.sig = function_sig();
      call.args.resize(call.sig->arg_names.size());
      call_details(call, false);
      pending_.emplace(call.number, std::make_pair(std::move(call), call_bytes_));
    } else if (event == kEventLeave) {
      const std::uint64_t number = uint();
      auto it = pending_.find(number);
      if (it == pending_.end()) fail(fmt::format("corrupt: a leave event for call {}, which is not pending", number));
      current_call_ = static_cast<long long>(number);
      Call call = std::move(it->second.first);
      call_bytes_ = it->second.second;
      pending_.erase(it);
      call_details(call, true);
      held_ -= call_bytes_;  // the caller owns it now
      call_bytes_ = 0;
      return call;
    } else {
      fail(fmt::format("corrupt: unknown event type 0x{:02x}", event));
    }
  }
}

}  // namespace passim::apitrace
