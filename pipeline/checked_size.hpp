// Sizes that come from input — a trace's counts and dimensions, the pixel-store modes, the
// lengths an apitrace file declares — are computed with this type: unsigned 64-bit, and an
// overflow or a negative operand is an error (SizeOverflow), never a wrapped value. Every
// byte count, element count and allocation size derived from input goes through it, so a
// length check cannot pass on a wrapped product (docs/hostile-input.md).
#pragma once
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace passim {

struct SizeOverflow : std::length_error {
  using std::length_error::length_error;
};

class CheckedSize {
 public:
  constexpr CheckedSize() = default;
  // Any integer; a negative one is an error (a size is never negative).
  template <class T, class = std::enable_if_t<std::is_integral_v<T>>>
  constexpr CheckedSize(T v) : value_(from(v)) {}  // NOLINT(google-explicit-constructor): sizes mix freely

  constexpr std::uint64_t value() const { return value_; }
  // The value as a std::size_t / int when it fits (it always fits size_t on 64-bit hosts).
  std::size_t as_size() const { return static_cast<std::size_t>(value_); }
  bool fits_int() const { return value_ <= static_cast<std::uint64_t>(std::numeric_limits<int>::max()); }

  friend CheckedSize operator+(CheckedSize a, CheckedSize b) {
    std::uint64_t r;
    if (__builtin_add_overflow(a.value_, b.value_, &r)) throw SizeOverflow("size overflows 64 bits");
    return raw(r);
  }
  friend CheckedSize operator*(CheckedSize a, CheckedSize b) {
    std::uint64_t r;
    if (__builtin_mul_overflow(a.value_, b.value_, &r)) throw SizeOverflow("size overflows 64 bits");
    return raw(r);
  }
  // a − b for a ≥ b; an error otherwise.
  friend CheckedSize operator-(CheckedSize a, CheckedSize b) {
    if (b.value_ > a.value_) throw SizeOverflow("size below zero");
    return raw(a.value_ - b.value_);
  }
  // ⌈a / b⌉ · b: a rounded up to a multiple of b (b > 0).
  static CheckedSize round_up(CheckedSize a, CheckedSize b) {
    if (b.value_ == 0) throw SizeOverflow("rounding to a multiple of 0");
    return CheckedSize(a.value_ / b.value_ + (a.value_ % b.value_ != 0)) * b;
  }
  CheckedSize& operator+=(CheckedSize b) { return *this = *this + b; }
  CheckedSize& operator*=(CheckedSize b) { return *this = *this * b; }
  friend constexpr auto operator<=>(CheckedSize a, CheckedSize b) = default;

 private:
  template <class T>
  static constexpr std::uint64_t from(T v) {
    if constexpr (std::is_signed_v<T>) {
      if (v < 0) throw SizeOverflow("negative size");
    }
    return static_cast<std::uint64_t>(v);
  }
  static CheckedSize raw(std::uint64_t v) {
    CheckedSize s;
    s.value_ = v;
    return s;
  }
  std::uint64_t value_ = 0;
};

}  // namespace passim
