#include "algo/kernels/pair_pass.hpp"

#include <algorithm>
#include <limits>
#include <variant>

namespace irloc {

PairPass::PairPass(const PairPassConfig& config)
    : config_(config), noise_(config.front_end.height, config.noise_rows), front_end_(config.front_end) {}

const PairAnalysis& PairPass::analyse(const GrayImageView& on, const GrayImageView& off) {
  on_ = on;
  off_ = off;
  analysis_.relabels = 0;
  analysis_.labelled_twice = false;
  analysis_.strobe = StrobeCounts{};
  // The threshold is known before the noise estimate when it is fixed, and expected to be the
  // floor (min_threshold) again when the last pair's was: a noise estimate far enough below the
  // floor does not lift it from one pair to the next (8-bit IR frames sit there). Then the pair is
  // labelled first, and the estimate's sampled rows are read where the labelling left them, in the
  // cache, not from memory (that reading was a fifth of a 640x480 8-bit pass). A threshold above
  // the floor moves with the noise from pair to pair (58 to 60 on rendered 12-bit drives) and would
  // cost a second labelling: it is estimated first.
  if (config_.fixed_threshold > 0) {
    analysis_.threshold = config_.fixed_threshold;
    label(true);
    estimate_noise();
    return analysis_;
  }
  const bool at_floor = last_threshold_ == config_.min_threshold;
  if (at_floor) {
    analysis_.threshold = config_.min_threshold;
    label(true);
  }
  estimate_noise();
  const std::uint32_t threshold = analysis_.noise.threshold(config_.threshold_sigmas, config_.min_threshold);
  last_threshold_ = threshold;
  if (!at_floor) {
    analysis_.threshold = threshold;
    label(true);
  } else if (threshold != config_.min_threshold) {
    // Labelled again at the pair's own threshold: the same blobs as if it had been the first.
    analysis_.threshold = threshold;
    analysis_.labelled_twice = true;
    label(false);
  }
  return analysis_;
}

void PairPass::estimate_noise() {
  analysis_.noise = std::visit(
      [&](const auto& on_view) {
        using View = std::decay_t<decltype(on_view)>;
        return noise_.estimate(on_view, std::get<View>(off_));
      },
      on_);
}

bool PairPass::relabel(std::uint32_t threshold) {
  if (analysis_.relabels == kMaxRelabels) return false;
  ++analysis_.relabels;
  analysis_.threshold = threshold;
  label(false);
  return true;
}

void PairPass::label(bool count_strobe) {
  std::visit(
      [&](const auto& on_view) {
        using View = std::decay_t<decltype(on_view)>;
        using Pixel = std::remove_const_t<typename std::remove_pointer_t<decltype(on_view.data())>>;
        // Thresholds beyond the depth flag nothing, as they would in wider arithmetic.
        const auto clamp = [](std::uint32_t value) {
          return static_cast<Pixel>(std::min<std::uint32_t>(value, std::numeric_limits<Pixel>::max()));
        };
        const View& off_view = std::get<View>(off_);
        const Pixel threshold = clamp(analysis_.threshold);
        analysis_.blob_counters =
            count_strobe ? front_end_.process(on_view, off_view, threshold,
                                              clamp(static_cast<std::uint32_t>(std::max(0, config_.strobe_noise_level))),
                                              analysis_.blobs, analysis_.strobe)
                         : front_end_.process(on_view, off_view, threshold, analysis_.blobs);
      },
      on_);
}

}  // namespace irloc
