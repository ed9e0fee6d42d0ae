#pragma once
// Fixed-point Q numbers for the integer image kernels.
//
// Q<F, Rep> stores a real number r as the integer raw = r * 2^F in Rep. In the usual Qm.n naming,
// Q<8, int32_t> is Q23.8 (sign, 23 integer bits, 8 fraction bits: 1/256 resolution).
//
// Rounding: every conversion that drops fraction bits (from_double, from_ratio, products,
// to_int) rounds to nearest with ties away from zero, so +x and -x round symmetrically.
// Saturation: a result that does not fit Rep is clamped to Rep's minimum or maximum; nothing
// ever wraps around. Division by zero saturates toward the sign of the numerator (0/0 is 0).

#include <cstdint>
#include <limits>
#include <type_traits>

namespace irloc {

// Clamps a wide integer into the range of Narrow.
template <typename Narrow, typename Wide>
constexpr Narrow saturate_cast(Wide value) {
  static_assert(std::is_integral_v<Narrow> && std::is_integral_v<Wide>);
  using Limits = std::numeric_limits<Narrow>;
  if constexpr (std::is_signed_v<Wide>) {
    if (value < 0 && static_cast<std::intmax_t>(value) < static_cast<std::intmax_t>(Limits::min())) {
      return Limits::min();
    }
  }
  if (value > 0 && static_cast<std::uintmax_t>(value) > static_cast<std::uintmax_t>(Limits::max())) {
    return Limits::max();
  }
  return static_cast<Narrow>(value);
}

// numerator / denominator rounded to nearest, ties away from zero, saturated to int64.
constexpr std::int64_t rounded_divide(std::int64_t numerator, std::int64_t denominator) {
  if (denominator == 0) {
    if (numerator == 0) return 0;
    return numerator > 0 ? std::numeric_limits<std::int64_t>::max()
                         : std::numeric_limits<std::int64_t>::min();
  }
  if (numerator == std::numeric_limits<std::int64_t>::min() && denominator == -1) {
    return std::numeric_limits<std::int64_t>::max();
  }
  std::int64_t quotient = numerator / denominator;  // truncated toward zero
  const std::int64_t remainder = numerator % denominator;
  // Magnitudes in unsigned arithmetic: |INT64_MIN| does not fit int64.
  const auto magnitude = [](std::int64_t x) {
    return x < 0 ? std::uint64_t{0} - static_cast<std::uint64_t>(x) : static_cast<std::uint64_t>(x);
  };
  const std::uint64_t remainder_size = magnitude(remainder);
  if (remainder_size >= magnitude(denominator) - remainder_size) {
    quotient += (numerator < 0) == (denominator < 0) ? 1 : -1;
  }
  return quotient;
}

template <int FractionBits, typename Rep = std::int32_t>
class Q {
  static_assert(std::is_integral_v<Rep> && std::is_signed_v<Rep>, "Q numbers are signed");
  static_assert(FractionBits >= 0 && FractionBits < static_cast<int>(sizeof(Rep) * 8) - 1);

 public:
  static constexpr int fraction_bits = FractionBits;
  static constexpr std::int64_t one_raw = std::int64_t{1} << FractionBits;

  constexpr Q() = default;

  static constexpr Q from_raw(Rep raw) { return Q(raw); }
  static constexpr Q from_int(std::int64_t value) {
    return Q(saturate_cast<Rep>(saturating_shift_left(value)));
  }
  // For start-up constants and tests; per-frame code stays in integers.
  static constexpr Q from_double(double value) {
    const double scaled = value * static_cast<double>(one_raw);
    const double rounded = scaled >= 0 ? scaled + 0.5 : scaled - 0.5;
    if (rounded >= static_cast<double>(std::numeric_limits<Rep>::max())) return Q(std::numeric_limits<Rep>::max());
    if (rounded <= static_cast<double>(std::numeric_limits<Rep>::min())) return Q(std::numeric_limits<Rep>::min());
    return Q(static_cast<Rep>(rounded));
  }
  // numerator / denominator in this format, e.g. a centroid sum(I x) / sum(I).
  static constexpr Q from_ratio(std::int64_t numerator, std::int64_t denominator) {
    return Q(saturate_cast<Rep>(rounded_divide(saturating_shift_left(numerator), denominator)));
  }

  constexpr Rep raw() const { return raw_; }
  constexpr double to_double() const { return static_cast<double>(raw_) / static_cast<double>(one_raw); }
  constexpr std::int64_t to_int() const { return rounded_divide(raw_, one_raw); }

  friend constexpr Q operator+(Q a, Q b) {
    return Q(saturate_cast<Rep>(static_cast<std::int64_t>(a.raw_) + b.raw_));
  }
  friend constexpr Q operator-(Q a, Q b) {
    return Q(saturate_cast<Rep>(static_cast<std::int64_t>(a.raw_) - b.raw_));
  }
  friend constexpr Q operator-(Q a) { return Q(saturate_cast<Rep>(-static_cast<std::int64_t>(a.raw_))); }
  // The product in the left operand's format: (a.raw * b.raw) / 2^(b's fraction bits), rounded.
  template <int OtherBits, typename OtherRep>
  friend constexpr Q operator*(Q a, Q<OtherBits, OtherRep> b) {
    const std::int64_t product = static_cast<std::int64_t>(a.raw_) * b.raw();
    return Q(saturate_cast<Rep>(rounded_divide(product, Q<OtherBits, OtherRep>::one_raw)));
  }
  friend constexpr auto operator<=>(Q a, Q b) = default;

 private:
  constexpr explicit Q(Rep raw) : raw_(raw) {}

  static constexpr std::int64_t saturating_shift_left(std::int64_t value) {
    constexpr std::int64_t limit = std::numeric_limits<std::int64_t>::max() >> FractionBits;
    if (value > limit) return std::numeric_limits<std::int64_t>::max();
    if (value < -limit) return std::numeric_limits<std::int64_t>::min();
    return value * one_raw;
  }

  Rep raw_ = 0;
};

// The formats the kernels use, by purpose.
using QPixel8 = Q<8, std::int32_t>;    // Q23.8: image coordinates to 1/256 px (centroids)
using QTrig14 = Q<14, std::int16_t>;   // Q1.14: sine/cosine table entries, |x| <= 1

}  // namespace irloc
