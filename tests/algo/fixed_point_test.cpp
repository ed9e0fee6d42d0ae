#include "algo/core/fixed_point.hpp"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace irloc {
namespace {

TEST(RoundedDivide, RoundsHalfAwayFromZero) {
  EXPECT_EQ(rounded_divide(5, 2), 3);
  EXPECT_EQ(rounded_divide(-5, 2), -3);
  EXPECT_EQ(rounded_divide(5, -2), -3);
  EXPECT_EQ(rounded_divide(-5, -2), 3);
  EXPECT_EQ(rounded_divide(7, 3), 2);
  EXPECT_EQ(rounded_divide(8, 3), 3);
  EXPECT_EQ(rounded_divide(-8, 3), -3);
  EXPECT_EQ(rounded_divide(0, 7), 0);
}

TEST(RoundedDivide, MatchesDoubleRoundingOnRandomInputs) {
  std::mt19937_64 random(1);
  std::uniform_int_distribution<std::int64_t> numerator(-1'000'000'000, 1'000'000'000);
  std::uniform_int_distribution<std::int64_t> denominator(1, 100'000);
  for (int i = 0; i < 100000; ++i) {
    const std::int64_t n = numerator(random);
    const std::int64_t d = denominator(random) * (i % 2 ? 1 : -1);
    const auto expected = static_cast<std::int64_t>(std::round(static_cast<double>(n) / static_cast<double>(d)));
    ASSERT_EQ(rounded_divide(n, d), expected) << n << " / " << d;
  }
}

TEST(RoundedDivide, SaturatesInsteadOfOverflowing) {
  constexpr auto max = std::numeric_limits<std::int64_t>::max();
  constexpr auto min = std::numeric_limits<std::int64_t>::min();
  EXPECT_EQ(rounded_divide(min, -1), max);
  EXPECT_EQ(rounded_divide(1, 0), max);
  EXPECT_EQ(rounded_divide(-1, 0), min);
  EXPECT_EQ(rounded_divide(0, 0), 0);
  EXPECT_EQ(rounded_divide(min, min), 1);
  EXPECT_EQ(rounded_divide(max, min), -1);
  EXPECT_EQ(rounded_divide(min, 2), min / 2);
}

TEST(SaturateCast, ClampsToTheNarrowRange) {
  EXPECT_EQ(saturate_cast<std::uint8_t>(300), 255);
  EXPECT_EQ(saturate_cast<std::uint8_t>(-4), 0);
  EXPECT_EQ(saturate_cast<std::int16_t>(-40000), -32768);
  EXPECT_EQ(saturate_cast<std::int16_t>(1234), 1234);
  EXPECT_EQ(saturate_cast<std::uint16_t>(std::uint64_t{1} << 40), 65535);
}

TEST(Q, ConvertsWithDocumentedRounding) {
  using Q8 = Q<8>;
  EXPECT_EQ(Q8::from_double(1.0).raw(), 256);
  EXPECT_EQ(Q8::from_double(1.5 / 256).raw(), 2);    // tie away from zero
  EXPECT_EQ(Q8::from_double(-1.5 / 256).raw(), -2);  // symmetric
  EXPECT_EQ(Q8::from_double(0.4 / 256).raw(), 0);
  EXPECT_DOUBLE_EQ(Q8::from_raw(384).to_double(), 1.5);
  EXPECT_EQ(Q8::from_raw(384).to_int(), 2);
  EXPECT_EQ(Q8::from_raw(-384).to_int(), -2);
  EXPECT_EQ(Q8::from_int(-3).raw(), -768);
}

TEST(Q, CentroidRatioHasQuarterByteResolution) {
  // sum(I x) / sum(I) of intensities 1 and 2 at x = 10 and 11: 10.666.. px
  const QPixel8 centroid = QPixel8::from_ratio(1 * 10 + 2 * 11, 3);
  EXPECT_NEAR(centroid.to_double(), 32.0 / 3.0, 0.5 / 256);
}

TEST(Q, ArithmeticSaturates) {
  using Q16 = Q<14, std::int16_t>;
  const Q16 almost_two = Q16::from_raw(32767);
  EXPECT_EQ((almost_two + almost_two).raw(), 32767);
  EXPECT_EQ((-almost_two - almost_two).raw(), -32768);
  EXPECT_EQ(Q16::from_double(5.0).raw(), 32767);
  EXPECT_EQ(Q16::from_int(-100).raw(), -32768);
  EXPECT_EQ((-Q16::from_raw(-32768)).raw(), 32767);
}

TEST(Q, ProductRoundsInTheLeftFormat) {
  const QPixel8 x = QPixel8::from_double(100.25);
  const QTrig14 half = QTrig14::from_double(0.5);
  EXPECT_DOUBLE_EQ((x * half).to_double(), 50.125);
  const QTrig14 sine = QTrig14::from_double(std::sin(0.3));
  EXPECT_NEAR((x * sine).to_double(), 100.25 * std::sin(0.3), 100.25 / 16384 + 1.0 / 256);
  EXPECT_EQ((Q<0>::from_int(3) * Q<1>::from_raw(1)).raw(), 2);  // 1.5 rounds to 2
  EXPECT_EQ((Q<0>::from_int(-3) * Q<1>::from_raw(1)).raw(), -2);
}

}  // namespace
}  // namespace irloc
