#include "algo/kernels/hough_lines.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>

#include "algo/kernels/simd_row.hpp"

namespace irloc {
namespace {

constexpr int kTrigShift = QTrig14::fraction_bits;

HoughConfig checked(const HoughConfig& config) {
  if (config.theta_bins < 2 || config.rho_resolution < 1 || config.rho_max < 1) {
    throw std::invalid_argument("HoughLines: theta_bins >= 2, rho_resolution >= 1 and rho_max >= 1 are required");
  }
  // The reciprocal binning is exact while (largest shifted rho) * resolution <= 2^32.
  const std::int64_t span = 2 * (static_cast<std::int64_t>(config.rho_max) + config.rho_resolution);
  if (span * config.rho_resolution > (std::int64_t{1} << 32)) {
    throw std::invalid_argument("HoughLines: rho_max * rho_resolution too large for 32-bit binning");
  }
  return config;
}

// The first r in [from, to] with row[r] >= at_least, or to + 1. Eight cells are tested at once
// while none reaches it: most of the accumulator holds a few stray votes below min_votes.
int next_at_least(const std::uint32_t* row, int from, int to, std::uint32_t at_least) {
  typedef std::uint32_t Cells __attribute__((vector_size(16)));
  int r = from;
  for (; r + 8 <= to + 1; r += 8) {
    Cells low, high;
    std::memcpy(&low, row + r, sizeof low);
    std::memcpy(&high, row + r + 4, sizeof high);
    const Cells reached = simd::vector_max(low, high) >= at_least;
    if ((reached[0] | reached[1] | reached[2] | reached[3]) != 0) break;
  }
  while (r <= to && row[r] < at_least) ++r;
  return r;
}

}  // namespace

HoughConfig HoughConfig::for_image(int width, int height) {
  HoughConfig config;
  config.rho_max = 256 * (width + height);
  config.max_points = std::min<std::size_t>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                                            std::size_t{1} << 16);
  return config;
}

HoughLines::HoughLines(const HoughConfig& config) : config_(checked(config)) {
  const std::int64_t centre = (config_.rho_max + config_.rho_resolution - 1) / config_.rho_resolution;
  rho_bins_ = static_cast<int>(2 * centre + 1);
  rho_offset_ = centre * config_.rho_resolution + config_.rho_resolution / 2;
  bin_reciprocal_ = ((std::uint64_t{1} << 32) + static_cast<std::uint64_t>(config_.rho_resolution) - 1) /
                    static_cast<std::uint64_t>(config_.rho_resolution);
  // theta_{n - k} = pi - theta_k: the table keeps cos(pi - t) = -cos(t) and sin(pi - t) = sin(t)
  // exact, which the vote relies on.
  const int bins = config_.theta_bins;
  cos_.resize(static_cast<std::size_t>(bins));
  sin_.resize(static_cast<std::size_t>(bins));
  for (int k = 0; k <= bins / 2; ++k) {
    const double theta = std::numbers::pi * k / bins;
    cos_[static_cast<std::size_t>(k)] = QTrig14::from_double(std::cos(theta));
    sin_[static_cast<std::size_t>(k)] = QTrig14::from_double(std::sin(theta));
    if (k > 0 && bins - k > bins / 2) {
      cos_[static_cast<std::size_t>(bins - k)] = QTrig14::from_raw(static_cast<std::int16_t>(-cos_[static_cast<std::size_t>(k)].raw()));
      sin_[static_cast<std::size_t>(bins - k)] = sin_[static_cast<std::size_t>(k)];
    }
  }
  accumulator_.resize(static_cast<std::size_t>(config_.theta_bins) * static_cast<std::size_t>(rho_bins_));
  image_points_.resize(config_.max_points);
}

std::int64_t HoughLines::rho_q8(PlanePoint p, int theta_bin) const {
  const std::int64_t sum = static_cast<std::int64_t>(p.x) * cos_[static_cast<std::size_t>(theta_bin)].raw() +
                           static_cast<std::int64_t>(p.y) * sin_[static_cast<std::size_t>(theta_bin)].raw();
  return (sum + (std::int64_t{1} << (kTrigShift - 1))) >> kTrigShift;  // round half up
}

HoughCounters HoughLines::detect(ImageView8 mask, HoughLineList& lines) {
  HoughCounters counters;
  std::size_t count = 0;
  for (int y = 0; y < mask.height(); ++y) {
    const std::uint8_t* row = mask.row(y);
    if (simd::max_value(row, mask.width()) == 0) continue;
    for (int x = 0; x < mask.width(); ++x) {
      if (row[x] == 0) continue;
      if (count == image_points_.size()) {
        ++counters.points_dropped;
        continue;
      }
      image_points_[count++] = {x * 256, y * 256};
    }
  }
  const HoughCounters voted = detect(std::span<const PlanePoint>(image_points_.data(), count), lines);
  counters.points = voted.points;
  counters.peaks = voted.peaks;
  counters.peaks_dropped = voted.peaks_dropped;
  return counters;
}

HoughCounters HoughLines::detect(std::span<const PlanePoint> points, HoughLineList& lines) {
  HoughCounters counters;
  lines.clear();
  std::int64_t radius_squared = 0;
  for (const PlanePoint& p : points) {
    radius_squared = std::max(radius_squared, static_cast<std::int64_t>(p.x) * p.x + static_cast<std::int64_t>(p.y) * p.y);
  }
  const auto radius = static_cast<std::int64_t>(std::sqrt(static_cast<double>(radius_squared))) + 2;
  const RhoBand band = band_within(radius);
  clear_accumulator(band);
  vote(points, radius <= config_.rho_max);
  counters.points = static_cast<std::uint32_t>(points.size());
  collect_peaks(band, lines, counters);
  for (HoughLine& line : lines) {
    if (config_.refine_peaks) {
      refine(points, line);
    } else {
      line.refined_theta = line.theta;
      line.refined_rho = line.rho;
    }
  }
  return counters;
}

int HoughLines::rho_bin_of(std::int64_t rho) const {
  const std::int64_t shifted = std::max<std::int64_t>(rho + rho_offset_, 0);
  return static_cast<int>(std::min((static_cast<std::uint64_t>(shifted) * bin_reciprocal_) >> 32,
                                   static_cast<std::uint64_t>(rho_bins_ - 1)));
}

// The votes fall within the points' largest radius (|x cos + y sin| <= |(x, y)|, plus the
// rounding); the band is kept symmetric, as the theta wrap mirrors rho, and widened by the
// suppression's reach.
HoughLines::RhoBand HoughLines::band_within(std::int64_t radius) const {
  if (config_.min_votes == 0) return {0, rho_bins_ - 1};  // empty cells can be peaks: every cell is scanned
  const int last = rho_bins_ - 1;
  return {std::max(0, std::min(rho_bin_of(-radius), last - rho_bin_of(radius)) - config_.nms_rho),
          std::min(last, std::max(rho_bin_of(radius), last - rho_bin_of(-radius)) + config_.nms_rho)};
}

// Zeroes the band and what the last detect() left outside it.
void HoughLines::clear_accumulator(RhoBand band) {
  const int clear_lo = std::min(band.lo, dirty_.lo), clear_hi = std::max(band.hi, dirty_.hi);
  for (int k = 0; k < config_.theta_bins && clear_lo <= clear_hi; ++k) {
    std::uint32_t* row = accumulator_.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(rho_bins_);
    std::fill(row + clear_lo, row + clear_hi + 1, 0u);
  }
  dirty_ = band;
}

// Peaks, strongest first; scanning in (theta, rho) order and inserting after equal votes keeps
// ties in scan order. A cell below a rho neighbour is no peak, whatever the rest of its
// neighbourhood: most cells are settled by these two.
void HoughLines::collect_peaks(RhoBand band, HoughLineList& lines, HoughCounters& counters) const {
  const int theta_bins = config_.theta_bins;
  const bool rho_neighbours = config_.nms_rho > 0;
  for (int k = 0; k < theta_bins; ++k) {
    const std::uint32_t* const row = accumulator_.data() + static_cast<std::size_t>(k) * static_cast<std::size_t>(rho_bins_);
    for (int r = next_at_least(row, band.lo, band.hi, config_.min_votes); r <= band.hi;
         r = next_at_least(row, r + 1, band.hi, config_.min_votes)) {
      const std::uint32_t v = row[r];
      if (rho_neighbours && ((r > 0 && row[r - 1] >= v) || (r + 1 < rho_bins_ && row[r + 1] > v))) continue;
      if (!is_peak(k, r, v)) continue;
      ++counters.peaks;
      if (lines.full()) {
        ++counters.peaks_dropped;
        if (lines.back().votes >= v) continue;
        lines.pop_back();
      }
      HoughLine line;
      line.theta_bin = k;
      line.rho_bin = r;
      line.votes = v;
      line.theta = std::numbers::pi * k / theta_bins;
      line.rho = rho_of(r);
      lines.push_back(line);
      for (std::size_t i = lines.size() - 1; i > 0 && lines[i - 1].votes < lines[i].votes; --i) {
        std::swap(lines[i - 1], lines[i]);
      }
    }
  }
}

// Theta by theta: a row stays in the first-level cache while every point votes in it, and
// neighbouring points that fall in one cell make a chain of dependent increments only within it.
void HoughLines::vote(std::span<const PlanePoint> points, bool within_rho_max) {
  const int bins = config_.theta_bins;
  const std::uint64_t reciprocal = bin_reciprocal_;
  const auto row = [this](int theta) {
    return accumulator_.data() + static_cast<std::size_t>(theta) * static_cast<std::size_t>(rho_bins_);
  };
  if (!within_rho_max) {  // rho clamped to the outermost bins
    const auto last_bin = static_cast<std::uint64_t>(rho_bins_ - 1);
    for (int theta = 0; theta < bins; ++theta) {
      std::uint32_t* const cells = row(theta);
      for (const PlanePoint& p : points) {
        const std::int64_t shifted = std::max<std::int64_t>(rho_q8(p, theta) + rho_offset_, 0);
        ++cells[std::min((static_cast<std::uint64_t>(shifted) * reciprocal) >> 32, last_bin)];
      }
    }
    return;
  }
  // Within rho_max nothing is clamped, and the offset added before the shift is the same as after.
  const std::int64_t rounded_offset = (rho_offset_ << kTrigShift) + (std::int64_t{1} << (kTrigShift - 1));
  const auto bin_of_sum = [reciprocal, rounded_offset](std::int64_t sum) {
    return (static_cast<std::uint64_t>((sum + rounded_offset) >> kTrigShift) * reciprocal) >> 32;
  };
  // theta and pi - theta share their products: x cos(pi - t) = -x cos(t), y sin(pi - t) = y sin(t).
  for (int theta = 1; theta < bins - theta; ++theta) {
    std::uint32_t* const cells = row(theta);
    std::uint32_t* const mirrored = row(bins - theta);
    const std::int64_t c = cos_[static_cast<std::size_t>(theta)].raw(), s = sin_[static_cast<std::size_t>(theta)].raw();
    for (const PlanePoint& p : points) {
      const std::int64_t x = p.x * c, y = p.y * s;
      ++cells[bin_of_sum(y + x)];
      ++mirrored[bin_of_sum(y - x)];
    }
  }
  for (const int theta : {0, bins / 2}) {  // their own mirrors (bins / 2 only when bins is even)
    if (theta != 0 && bins - theta != theta) continue;
    std::uint32_t* const cells = row(theta);
    const std::int64_t c = cos_[static_cast<std::size_t>(theta)].raw(), s = sin_[static_cast<std::size_t>(theta)].raw();
    for (const PlanePoint& p : points) ++cells[bin_of_sum(p.x * c + p.y * s)];
  }
}

bool HoughLines::is_peak(int theta_bin, int rho_bin, std::uint32_t v) const {
  const int theta_bins = config_.theta_bins;
  if (theta_bin >= config_.nms_theta && theta_bin + config_.nms_theta < theta_bins && rho_bin >= config_.nms_rho &&
      rho_bin + config_.nms_rho < rho_bins_) {  // inside: no wrap, no edge
    for (int dk = -config_.nms_theta; dk <= config_.nms_theta; ++dk) {
      const std::uint32_t* row = &accumulator_[static_cast<std::size_t>(theta_bin + dk) * static_cast<std::size_t>(rho_bins_) +
                                               static_cast<std::size_t>(rho_bin)];
      for (int dr = -config_.nms_rho; dr <= config_.nms_rho; ++dr) {
        const std::uint32_t u = row[dr];
        // On a plateau the first cell in scan order wins.
        if (dk < 0 || (dk == 0 && dr < 0) ? u >= v : u > v) return false;  // the centre: u == v
      }
    }
    return true;
  }
  for (int dk = -config_.nms_theta; dk <= config_.nms_theta; ++dk) {
    for (int dr = -config_.nms_rho; dr <= config_.nms_rho; ++dr) {
      if (dk == 0 && dr == 0) continue;
      int k = theta_bin + dk;
      int r = rho_bin + dr;
      // theta and theta + pi are the same line with rho negated: wrap and mirror.
      if (k < 0 || k >= theta_bins) {
        k = (k + theta_bins) % theta_bins;
        r = rho_bins_ - 1 - r;
      }
      if (r < 0 || r >= rho_bins_) continue;
      const std::uint32_t u = votes(k, r);
      // On a plateau the first cell in scan order wins.
      const bool neighbour_first = dk < 0 || (dk == 0 && dr < 0);
      if (neighbour_first ? u >= v : u > v) return false;
    }
  }
  return true;
}

void HoughLines::refine(std::span<const PlanePoint> points, HoughLine& line) const {
  const std::int64_t line_rho = static_cast<std::int64_t>(line.rho_bin - rho_bins_ / 2) * config_.rho_resolution;
  // Exact integer sums, relative to the first inlier so that they stay small (|d| < 2^23, n < 2^16).
  std::int64_t n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  PlanePoint origin;
  for (const PlanePoint& p : points) {
    const std::int64_t distance = rho_q8(p, line.theta_bin) - line_rho;
    if (distance > config_.inlier_distance || distance < -config_.inlier_distance) continue;
    if (n == 0) origin = p;
    const std::int64_t dx = p.x - origin.x;
    const std::int64_t dy = p.y - origin.y;
    ++n;
    sx += dx;
    sy += dy;
    sxx += dx * dx;
    syy += dy * dy;
    sxy += dx * dy;
  }
  line.inliers = static_cast<std::uint32_t>(n);
  line.refined_theta = line.theta;
  line.refined_rho = line.rho;
  if (n < 2) return;
  // Total least squares: the line through the mean along the principal axis of the scatter.
  const double count = static_cast<double>(n);
  const double mx = static_cast<double>(sx) / count;
  const double my = static_cast<double>(sy) / count;
  const double cxx = static_cast<double>(sxx) / count - mx * mx;
  const double cyy = static_cast<double>(syy) / count - my * my;
  const double cxy = static_cast<double>(sxy) / count - mx * my;
  double theta = 0.5 * std::atan2(2.0 * cxy, cxx - cyy) + std::numbers::pi / 2;  // normal of the major axis
  double rho = ((origin.x + mx) * std::cos(theta) + (origin.y + my) * std::sin(theta)) / 256.0;
  if (theta >= std::numbers::pi) {
    theta -= std::numbers::pi;
    rho = -rho;
  }
  line.refined_theta = theta;
  line.refined_rho = rho;
}

}  // namespace irloc
