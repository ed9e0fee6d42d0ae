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
  analysis_.strobe = StrobeCounts{};
  analysis_.noise = std::visit(
      [&](const auto& on_view) {
        using View = std::decay_t<decltype(on_view)>;
        return noise_.estimate(on_view, std::get<View>(off));
      },
      on);
  analysis_.threshold = config_.fixed_threshold > 0 ? config_.fixed_threshold
                                                    : analysis_.noise.threshold(config_.threshold_sigmas, config_.min_threshold);
  label(true);
  return analysis_;
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
