#pragma once
// Per-blob statistics, as the connected-components kernels report them.
//
// Every statistic is an exact integer sum over the blob's pixels (x, y: pixel indices, the
// pixel centre convention of the spec; I: the pixel's intensity, which for the strobe pair is the
// difference on - off). Derived values (centroids, moments) are formed once from those sums:
// as double (exact to double rounding: well inside 1e-6 px) or as QPixel8 (Q23.8, rounded to the
// nearest 1/256 px, ties away from zero). Sums are unsigned 64-bit: they cannot overflow while
// area * max intensity * max(width, height)^2 < 2^64, e.g. any frame up to 2048 x 2048 at 16 bits.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "algo/core/fixed_point.hpp"
#include "algo/core/static_vector.hpp"

namespace irloc {

// Blobs kept per frame; further blobs are counted (BlobList::dropped()), not kept.
inline constexpr std::size_t kMaxBlobs = 256;

struct Blob {
  std::uint32_t area = 0;                    // pixels
  int x_min = 0, y_min = 0, x_max = 0, y_max = 0;  // bounding box, inclusive
  std::uint64_t sum_x = 0, sum_y = 0;        // sum of x, of y (unweighted)
  std::uint64_t sum_i = 0;                   // sum of I (> 0: every pixel has I >= 1)
  std::uint64_t sum_ix = 0, sum_iy = 0;      // sum of I x, I y
  std::uint64_t sum_ixx = 0, sum_iyy = 0, sum_ixy = 0;
  std::uint32_t peak = 0;                    // largest I

  int width() const { return x_max - x_min + 1; }
  int height() const { return y_max - y_min + 1; }

  // Intensity-weighted centroid, px.
  double centroid_x() const { return exact_ratio(sum_ix, sum_i); }
  double centroid_y() const { return exact_ratio(sum_iy, sum_i); }
  QPixel8 centroid_x_q8() const { return ratio_q8(sum_ix, sum_i); }
  QPixel8 centroid_y_q8() const { return ratio_q8(sum_iy, sum_i); }
  // Unweighted (geometric) centroid, px: what cv::connectedComponentsWithStats reports.
  double geometric_centroid_x() const { return exact_ratio(sum_x, area); }
  double geometric_centroid_y() const { return exact_ratio(sum_y, area); }
  double mean_intensity() const { return exact_ratio(sum_i, area); }

  // Intensity-weighted central second moments, px^2 (variances and covariance of x, y).
  double mu_xx() const { return central(sum_ixx, sum_ix, sum_ix); }
  double mu_yy() const { return central(sum_iyy, sum_iy, sum_iy); }
  double mu_xy() const { return central(sum_ixy, sum_ix, sum_iy); }
  // Angle of the major axis from +x toward +y (image y down), radians in (-pi/2, pi/2].
  double orientation() const { return 0.5 * std::atan2(2.0 * mu_xy(), mu_xx() - mu_yy()); }
  // Variances along the major and minor axes (eigenvalues of the moment matrix), px^2.
  double major_variance() const { return 0.5 * (mu_xx() + mu_yy()) + half_eigen_gap(); }
  double minor_variance() const { return std::max(0.0, 0.5 * (mu_xx() + mu_yy()) - half_eigen_gap()); }
  // sqrt(major / minor) >= 1: 1 for a round blob, +inf for a one-pixel-wide line.
  double elongation() const {
    const double minor = minor_variance();
    return minor > 0 ? std::sqrt(major_variance() / minor) : std::numeric_limits<double>::infinity();
  }

 private:
  __extension__ typedef __int128 Int128;

  // numerator / denominator without the rounding of converting a large numerator to double.
  static double exact_ratio(std::uint64_t numerator, std::uint64_t denominator) {
    return static_cast<double>(numerator / denominator) +
           static_cast<double>(numerator % denominator) / static_cast<double>(denominator);
  }
  static QPixel8 ratio_q8(std::uint64_t numerator, std::uint64_t denominator) {
    const auto whole = static_cast<std::int64_t>(numerator / denominator);
    const auto remainder = static_cast<std::int64_t>(numerator % denominator);
    return QPixel8::from_raw(saturate_cast<std::int32_t>(
        whole * QPixel8::one_raw + rounded_divide(remainder * QPixel8::one_raw, static_cast<std::int64_t>(denominator))));
  }
  // (S * s_ab - s_a * s_b) / S^2, the numerator exact in 128 bits.
  double central(std::uint64_t s_ab, std::uint64_t s_a, std::uint64_t s_b) const {
    const Int128 numerator = static_cast<Int128>(sum_i) * s_ab - static_cast<Int128>(s_a) * s_b;
    const double s = static_cast<double>(sum_i);
    return static_cast<double>(numerator) / (s * s);
  }
  double half_eigen_gap() const {
    const double half_difference = 0.5 * (mu_xx() - mu_yy());
    return std::sqrt(half_difference * half_difference + mu_xy() * mu_xy());
  }
};

using BlobList = StaticVector<Blob, kMaxBlobs>;

}  // namespace irloc
