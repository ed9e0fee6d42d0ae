#pragma once
// The box's pose refined against the pixels themselves, for a robot the foreground shows only in
// part (faces as bright as the floor behind them: docs/outside_in.md, "The appearance fit"). Every
// pixel of a region around the box shows either the floor (the learned background, rescaled for
// the light) or one of the box's visible faces: the top one shade, each visible side kBands shades,
// one per band of its height (a bumper, a strip). Each shade is the mean of the frame over the
// pixels it covers at that pose. The cost is the sum over the region of min(residual^2,
// kTruncation^2): where a face matches the floor behind it, both explain the pixel alike and it says
// nothing; the pose rests on the pixels where they differ (a face over the other tile, a joint, a
// face against another face). Coordinate descent from each start pose over (x, y, yaw) with
// halving steps, over one region (every start's outline and a margin), so that where the starts
// end in different minima the lower cost decides. Bounded work: at most kMaxStarts starts, each at
// most kMaxEvaluations costs, each over at most kMaxSamples pixels (a larger region is sampled
// every other pixel or sparser). Allocation-free.
//
// The shades are fitted at each pose, so the cost is the same at yaw and yaw + pi: the fit gives
// the heading modulo the box's half turn, as the silhouette fit does.
#include <array>
#include <span>

#include "algo/core/image_view.hpp"
#include "algo/markers/outside_in/adaptive_background.hpp"
#include "algo/markers/outside_in/box_silhouette.hpp"

namespace irloc::outside_in {

inline constexpr int kFaceBands = 6;  // bands of a side's height, each its own shade

// An end face as a fit saw it, for telling the robot's front from its back (end_face_looks.hpp).
struct EndView {
  static constexpr int kMinBandSamples = 6;  // of each band and of the top, else no view
  // Of the box's samples, outliers at most (a fit 44 mm off left 0.041, fits on the robot 0.001-0.023
  // in the light robot's scenario): a person over an end face changes its shades.
  static constexpr double kMaxBoxOutliers = 0.03;
  int side = 0;  // +1: the end at the fitted pose's +x; -1: the one at -x; 0: no end seen well enough
  std::array<double, kFaceBands> ratio{};  // each band's shade over the top's, the bottom band first
};

struct AppearanceFit {
  // Taken as the robot (measured on rendered rooms, docs/outside_in.md): fits within 2 cm leave at
  // most 0.094 of the box's samples outliers, fits farther off mostly more; the samples around the
  // box are more often outliers (the contact shadow, a background that learned part of a robot
  // standing at start-up) but not most of them, unless the box sits inside another mover; and a box
  // must differ from the floor behind it over part of itself, else a box anywhere on a uniform tile
  // explains its pixels as well.
  static constexpr double kMaxBoxOutliers = 0.10;
  static constexpr double kMaxAroundOutliers = 0.60;
  static constexpr double kMinContrast = 0.30;

  bool ok = false;                    // the cost could be evaluated at a start (the box in view)
  FloorPose pose;                     // yaw modulo the box's symmetry turn, as the start's
  double box_outlier_fraction = 0;    // of the box's samples, a residual beyond the truncation
  double around_outlier_fraction = 0; // of the samples around the box, the same
  double contrast_fraction = 0;       // of the box's samples, its face's shade differing from the floor behind by the truncation
  int evaluations = 0;                // costs evaluated, over all starts
  EndView end;                        // at `pose`

  bool explains_robot() const {
    return ok && box_outlier_fraction <= kMaxBoxOutliers && around_outlier_fraction <= kMaxAroundOutliers &&
           contrast_fraction >= kMinContrast;
  }
};

class AppearanceFitter {
 public:
  static constexpr int kBands = kFaceBands;
  static constexpr int kMaxFaces = 1 + 2 * kBands;  // a box shows at most its top and two sides
  static constexpr double kTruncation = 8;          // grey levels (5 sigma of the rendered sensor noise)
  static constexpr int kMaxEvaluations = 160;     // per start
  static constexpr int kMaxStarts = 2;
  static constexpr int kMaxSamples = 160 * 160;
  static constexpr int kMarginPx = 6;               // the region: the start's silhouette and this much around it
  static constexpr double kFirstStepM = 0.02;       // halved kLevels - 1 times
  static constexpr double kFirstStepRad = 0.04;
  static constexpr int kLevels = 4;
  static constexpr int kMaxWidth = 4096;          // px: the image's widest (a row's faces are kept on the stack)

  // A width over kMaxWidth: std::invalid_argument.
  AppearanceFitter(const BoxSilhouette& box, int width, int height);

  // The pose near one of `starts` that the frame's pixels fit best (above). More than kMaxStarts
  // starts: std::invalid_argument.
  AppearanceFit refine(ImageView8 frame, const AdaptiveBackground& background, std::span<const FloorPose> starts) const;
  AppearanceFit refine(ImageView8 frame, const AdaptiveBackground& background, const FloorPose& start) const {
    return refine(frame, background, std::span<const FloorPose>(&start, 1));
  }

 private:
  struct Region {
    int x_min = 0, y_min = 0, x_max = -1, y_max = -1;
    int step = 1;  // pixels sampled every `step` in x and y
  };
  struct Cost {
    bool ok = false;
    double value = 0;
    int samples = 0, outliers = 0, box_samples = 0, box_outliers = 0, contrasted = 0;
    // Per face (the top first, then an end's bands if one is seen, then a side's): its shade, and
    // the samples it covers; the end seen (EndView::side, 0 for none).
    std::array<double, kMaxFaces> shade{};
    std::array<int, kMaxFaces> covered{};
    int end_side = 0;
    EndView end_view() const;
  };
  // Not ok when the box is out of view, or when the cost passes `give_up_above` (it is then only
  // known to be larger: the descent's candidates against its best so far).
  Cost cost(ImageView8 frame, const AdaptiveBackground& background, const Region& region, const FloorPose& pose,
            double give_up_above) const;
  // The descent from `pose` (moved to its end); its cost there, and the evaluations it took added.
  Cost descend(ImageView8 frame, const AdaptiveBackground& background, const Region& region, FloorPose& pose,
               int& evaluations) const;

  const BoxSilhouette& box_;
  int width_, height_;
};

}  // namespace irloc::outside_in
