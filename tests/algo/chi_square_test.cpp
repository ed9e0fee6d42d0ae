// algo/core/chi_square: the quantiles against tabulated values (Abramowitz and Stegun, tables 26.1
// and 26.8; exact values from any statistics package).

#include <gtest/gtest.h>

#include "algo/core/chi_square.hpp"

namespace irloc {
namespace {

TEST(ChiSquare, NormalQuantileMatchesTheTable) {
  EXPECT_NEAR(normal_upper_quantile(0.5), 0.0, 1e-12);
  EXPECT_NEAR(normal_upper_quantile(0.025), 1.959964, 1e-6);
  EXPECT_NEAR(normal_upper_quantile(0.001), 3.090232, 1e-6);
  EXPECT_NEAR(normal_upper_quantile(1e-6), 4.753424, 1e-6);
}

// Wilson-Hilferty's cube errs high in the far tail of few degrees: 1.8 % at 3 degrees and tail
// 0.001, 0.6 % at 10, less with more degrees or a wider tail.
TEST(ChiSquare, QuantileIsWithinTwoPercentOfTheTable) {
  struct Row {
    int degrees;
    double tail, exact, tolerance;
  };
  for (const Row row : {Row{3, 0.001, 16.266, 0.02}, Row{10, 0.001, 29.588, 0.007}, Row{10, 0.05, 18.307, 0.002},
                        Row{24, 0.01, 42.980, 0.002}, Row{100, 0.001, 149.449, 0.002}}) {
    const double quantile = chi_square_quantile(row.degrees, row.tail);
    EXPECT_NEAR(quantile / row.exact, 1.0, row.tolerance) << row.degrees << " degrees, tail " << row.tail;
    EXPECT_DOUBLE_EQ(quantile, chi_square_quantile_at(row.degrees, normal_upper_quantile(row.tail)));
  }
}

}  // namespace
}  // namespace irloc
