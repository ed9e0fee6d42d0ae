#pragma once
// The robot's two end faces as appearance fits see them (EndView: each band's shade over the top's,
// so that a lamp step or the exposure, which scale both, does not change them), learned from the
// views of tracks that know the robot's front. A track that does not (one an appearance fit began
// mid-drive, or a robot turning in place) takes its heading's branch from them once they tell the
// ends apart, instead of waiting for a metre of travel (travel_branch.hpp; docs/outside_in.md, "The
// appearance fit"). One robot per camera: the looks are the source's, kept across its tracks.
#include <array>
#include <cmath>

#include "algo/markers/outside_in/appearance_fit.hpp"

namespace irloc::outside_in {

class EndFaceLooks {
 public:
  static constexpr int kMinViews = 10;       // of each end before they tell
  static constexpr double kMinApart = 0.08;  // the ends' mean ratios this far apart (RMS over bands), else alike
  static constexpr double kMargin = 0.5;     // a view nearer one end than the other by this share of their distance
  static constexpr double kOtherEnd = 0.15;  // a view this far from the only end learned is of the other end

  // A view of the front (or of the back); views with no end seen are ignored.
  void learn(const EndView& view, bool front) {
    if (view.side == 0) return;
    Mean& end = front ? front_ : back_;
    for (std::size_t band = 0; band < view.ratio.size(); ++band) end.sum[band] += view.ratio[band];
    ++end.views;
  }

  // +1: the view is of the front; -1: of the back; 0: it does not tell (no end seen, neither end
  // seen kMinViews times, the ends alike, the view between them). With one end learned, only a view
  // far from it tells (of the other end): a view like it may be of the other end looking alike.
  int tell(const EndView& view) const {
    const bool front_learned = front_.views >= kMinViews, back_learned = back_.views >= kMinViews;
    if (view.side == 0 || !(front_learned || back_learned)) return 0;
    if (front_learned != back_learned) {
      const Ratios learned = front_learned ? front_.mean() : back_.mean();
      return rms_difference(view.ratio, learned) >= kOtherEnd ? (front_learned ? -1 : 1) : 0;
    }
    const Ratios front = front_.mean(), back = back_.mean();
    const double apart = rms_difference(front, back);
    if (apart < kMinApart) return 0;
    const double to_front = rms_difference(view.ratio, front), to_back = rms_difference(view.ratio, back);
    if (to_back - to_front >= kMargin * apart) return 1;
    if (to_front - to_back >= kMargin * apart) return -1;
    return 0;
  }

 private:
  using Ratios = std::array<double, kFaceBands>;
  struct Mean {
    Ratios sum{};
    int views = 0;
    Ratios mean() const {
      Ratios m{};
      for (std::size_t band = 0; band < m.size(); ++band) m[band] = sum[band] / views;
      return m;
    }
  };
  static double rms_difference(const Ratios& a, const Ratios& b) {
    double sum = 0;
    for (std::size_t band = 0; band < a.size(); ++band) sum += (a[band] - b[band]) * (a[band] - b[band]);
    return std::sqrt(sum / static_cast<double>(a.size()));
  }

  Mean front_, back_;
};

}  // namespace irloc::outside_in
