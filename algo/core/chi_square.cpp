#include "algo/core/chi_square.hpp"

#include <cmath>

namespace irloc {

double normal_upper_quantile(double tail) {
  double low = 0, high = 40;
  for (int i = 0; i < 200; ++i) {
    const double middle = (low + high) / 2;
    (0.5 * std::erfc(middle / std::sqrt(2.0)) > tail ? low : high) = middle;
  }
  return (low + high) / 2;
}

double chi_square_quantile_at(int degrees, double normal_quantile) {
  const double k = degrees;
  const double spread = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - spread + normal_quantile * std::sqrt(spread), 3);
}

double chi_square_quantile(int degrees, double tail) {
  return chi_square_quantile_at(degrees, normal_upper_quantile(tail));
}

}  // namespace irloc
