#pragma once
// Hough transform for straight lines, rho = x cos(theta) + y sin(theta), over a fixed-point trig
// table, with non-maximum suppression and (unless refine_peaks is off) a least-squares refinement
// of each peak.
//
// Points are PlanePoint: Q23.8 coordinates (raw / 256 = units: px for an image, or any plane unit,
// e.g. the ceiling plane of the square-marker path). theta_k = k * pi / theta_bins, k in
// [0, theta_bins); cos/sin are QTrig14 (Q1.14). rho bins are rho_resolution wide (Q23.8), centred
// on 0: bin b holds rho in [(b - c - 1/2) res, (b - c + 1/2) res) with c = rho_bins / 2, rho of a vote
// being x cos + y sin rounded to 1/256 (half up) first. Votes are 32-bit counts.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "algo/core/fixed_point.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/static_vector.hpp"

namespace irloc {

struct PlanePoint {
  std::int32_t x = 0;  // Q23.8 raw
  std::int32_t y = 0;
};

struct HoughConfig {
  int theta_bins = 180;               // pi / theta_bins rad per bin
  std::int32_t rho_resolution = 256;  // Q23.8 raw: 256 = 1 unit
  std::int32_t rho_max = 256 * 2048;  // Q23.8 raw: lines with |rho| <= rho_max are found
  std::size_t max_points = std::size_t{1} << 16;  // image pixels collected per detect()
  std::uint32_t min_votes = 20;       // a peak needs at least this many votes
  int nms_rho = 2;                    // a peak is the maximum of its (2 nms_rho + 1) x
  int nms_theta = 2;                  // (2 nms_theta + 1) neighbourhood (theta wraps, rho mirrored)
  std::int32_t inlier_distance = 256;  // Q23.8 raw: points this close to a peak's line refine it
  bool refine_peaks = true;  // false: a peak's refined line is its cell's, with 0 inliers

  // Covers every line through a width x height image at 1 px and 1 degree.
  static HoughConfig for_image(int width, int height);
};

struct HoughLine {
  int theta_bin = 0;
  int rho_bin = 0;
  std::uint32_t votes = 0;
  double theta = 0;  // the peak's cell centre: rad in [0, pi)
  double rho = 0;    // units (raw / 256)
  // Total least squares on the inliers of the peak's line; theta in [0, pi), rho in units.
  double refined_theta = 0;
  double refined_rho = 0;
  std::uint32_t inliers = 0;
};

inline constexpr std::size_t kMaxHoughLines = 32;
// Strongest first (ties: smaller theta_bin, then rho_bin, first).
using HoughLineList = StaticVector<HoughLine, kMaxHoughLines>;

struct HoughCounters {
  std::uint32_t points = 0;          // points that voted
  std::uint32_t points_dropped = 0;  // image pixels beyond max_points
  std::uint32_t peaks = 0;           // cells that passed min_votes and non-maximum suppression
  std::uint32_t peaks_dropped = 0;   // the weakest peaks beyond kMaxHoughLines
};

class HoughLines {
 public:
  // Allocates the accumulator (theta_bins x rho_bins votes), trig table and point buffer here.
  // Throws std::invalid_argument for a configuration whose fixed-point arithmetic could overflow.
  explicit HoughLines(const HoughConfig& config);

  // Every nonzero pixel (x, y) of the mask votes as the point (x, y) px.
  HoughCounters detect(ImageView8 mask, HoughLineList& lines);
  // Every point votes (its rho clamped to the outermost bins if beyond rho_max); |coordinates|
  // must stay below 2^22 raw (16384 units) and points.size() below 2^16.
  HoughCounters detect(std::span<const PlanePoint> points, HoughLineList& lines);

  int theta_bins() const { return config_.theta_bins; }
  int rho_bins() const { return rho_bins_; }
  // The rho of a bin's centre, units.
  double rho_of(int rho_bin) const {
    return static_cast<double>((rho_bin - rho_bins_ / 2) * static_cast<std::int64_t>(config_.rho_resolution)) / 256.0;
  }
  // The votes of the last detect() in a cell.
  std::uint32_t votes(int theta_bin, int rho_bin) const {
    return accumulator_[static_cast<std::size_t>(theta_bin) * static_cast<std::size_t>(rho_bins_) +
                        static_cast<std::size_t>(rho_bin)];
  }
  QTrig14 cos_of(int theta_bin) const { return cos_[static_cast<std::size_t>(theta_bin)]; }
  QTrig14 sin_of(int theta_bin) const { return sin_[static_cast<std::size_t>(theta_bin)]; }

 private:
  struct RhoBand {  // rho bins [lo, hi]
    int lo = 0;
    int hi = -1;
  };

  std::int64_t rho_q8(PlanePoint p, int theta_bin) const;  // x cos + y sin, Q23.8, rounded
  int rho_bin_of(std::int64_t rho) const;                  // rho Q23.8, clamped to the bins
  // The bins the votes of points within `radius` (Q23.8) can reach, or whose peaks they decide.
  RhoBand band_within(std::int64_t radius) const;
  void clear_accumulator(RhoBand band);
  // Every point votes once per theta (all points within rho_max: no clamping needed).
  void vote(std::span<const PlanePoint> points, bool within_rho_max);
  bool is_peak(int theta_bin, int rho_bin, std::uint32_t votes) const;
  void refine(std::span<const PlanePoint> points, HoughLine& line) const;
  void collect_peaks(RhoBand band, HoughLineList& lines, HoughCounters& counters) const;

  HoughConfig config_;
  int rho_bins_ = 0;
  std::int64_t rho_offset_ = 0;        // Q23.8: added to rho so bins start at 0
  std::uint64_t bin_reciprocal_ = 0;   // ceil(2^32 / rho_resolution)
  std::vector<QTrig14> cos_;
  std::vector<QTrig14> sin_;
  std::vector<std::uint32_t> accumulator_;
  // Every cell outside this band (all thetas) is 0: a detect() clears and scans only the band its
  // points' radius can reach.
  RhoBand dirty_;
  std::vector<PlanePoint> image_points_;
};

}  // namespace irloc
