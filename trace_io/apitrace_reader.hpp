// Reading apitrace's binary .trace files (apitrace docs/FORMAT.markdown): the
// snappy-chunked stream, the header and properties, and the call events with their
// values exactly as recorded (floats and doubles bit for bit).
#pragma once
#include <cstdint>
#include <istream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace passim::apitrace {

// A malformed, truncated or unsupported trace; `call` is the number of the call being
// read (or the last one read), -1 before the first.
struct FormatError : std::runtime_error {
  FormatError(long long call, const std::string& message);
  long long call;
};

// One recorded value (FORMAT.markdown "Values").
struct Value {
  enum class Kind : std::uint8_t {
    Null, False, True, SInt, UInt, Float, Double, String, Blob, Enum, Bitmask, Array, Struct, Pointer, Repr, WString
  };
  Kind kind = Kind::Null;
  std::int64_t i = 0;   // SInt, Enum (signed value), Bool (0/1)
  std::uint64_t u = 0;  // UInt, Bitmask, Pointer
  double d = 0.0;       // Float (widened exactly), Double
  std::string bytes;    // String (UTF-8), Blob; the enum's name for Enum when known
  std::vector<Value> items;  // Array, Struct members; Repr: {human, machine}

  bool is_integer() const;  // SInt, UInt, Enum, Bitmask, False, True
  std::int64_t as_integer() const;  // the integer of any of those (UInt above int64 wraps)
  bool is_number() const { return is_integer() || kind == Kind::Float || kind == Kind::Double; }
  double as_double() const;
};

struct FunctionSig {
  std::string name;
  std::vector<std::string> arg_names;
};

struct Call {
  std::uint64_t number = 0;
  std::uint64_t thread = 0;
  std::shared_ptr<const FunctionSig> sig;
  std::vector<std::optional<Value>> args;  // one per sig argument; empty when not recorded
  std::optional<Value> ret;
  bool fake = false;        // FLAG_FAKE: inserted by apitrace, not made by the program
  bool incomplete = false;  // the trace ended before the call's leave event
  const std::string& name() const { return sig->name; }
};

inline constexpr unsigned kOldestVersion = 1, kNewestVersion = 6;

// Reads calls one at a time, in the order they completed.
class Reader {
 public:
  // `in` must outlive the reader. Throws FormatError for a file that is not a
  // snappy-compressed apitrace trace or has an unsupported version. The reader holds at most
  // `max_held_bytes` of decoded values and signatures at once (the calls not yet returned and
  // the signatures it has met): a file whose values need more is refused (FormatError), as a
  // few megabytes of compressed nulls can expand to gigabytes of values.
  explicit Reader(std::istream& in, std::uint64_t max_held_bytes = std::uint64_t{256} << 20);
  ~Reader();

  unsigned version() const { return version_; }
  const std::map<std::string, std::string>& properties() const { return properties_; }
  // The next call, or nothing at the end of the trace. Throws FormatError.
  std::optional<Call> next();

 private:
  // Bytes of the decompressed stream.
  bool fill();
  std::uint8_t byte();
  std::uint64_t uint();
  // Which count the bytes of what is read go to: the call being read, or the signatures kept.
  enum class Held { Call, Signature };
  std::string string(Held held);
  void hold(std::uint64_t bytes, Held held);
  float read_float();
  double read_double();
  Value value(int depth = 0);
  void call_details(Call& call, bool leave);
  std::shared_ptr<const FunctionSig> function_sig();
  [[noreturn]] void fail(const std::string& message) const;

  std::istream& in_;
  std::string chunk_;
  std::size_t pos_ = 0;
  bool eof_ = false;
  bool magic_read_ = false;
  unsigned version_ = 0;
  std::map<std::string, std::string> properties_;
  std::unordered_map<std::uint64_t, std::shared_ptr<const FunctionSig>> functions_;
  std::unordered_map<std::uint64_t, std::vector<std::pair<std::string, std::int64_t>>> enums_;
  std::unordered_map<std::uint64_t, bool> bitmasks_;
  std::unordered_map<std::uint64_t, std::size_t> structs_;  // member counts
  std::unordered_map<std::uint64_t, bool> frames_;
  std::map<std::uint64_t, std::pair<Call, std::uint64_t>> pending_;  // entered, not yet left; their bytes
  std::uint64_t max_held_ = 0;
  std::uint64_t held_ = 0;        // signatures, pending calls and the call being read
  std::uint64_t call_bytes_ = 0;  // the call being read
  std::uint64_t next_call_ = 0;
  long long current_call_ = -1;
};

}  // namespace passim::apitrace
