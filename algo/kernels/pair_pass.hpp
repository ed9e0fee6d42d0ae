#pragma once
// The one pass over a strobe pair that every pose source shares (the Localizer runs it once per
// pair, before the sources): the fused front end at the blobs' threshold, which in the same vector
// pass counts the strobe check's evidence (strobe_check.hpp), and the noise of the difference
// (difference_noise.hpp, sampled rows), from which that threshold is derived. Where the threshold
// is fixed, or expected at its floor again, the pass labels before it estimates the noise (the
// sampled rows are then in the cache), and labels again, once, where the pair's own threshold
// differs: the blobs are always those at the pair's own threshold. A source that needs the blobs at
// another threshold asks for a relabelling, bounded per pair. The foreground's runs stay readable
// until the next labelling (the square path builds its tape mask from them).
//
//   PairPass pass(config);                              // start-up: the only allocations
//   const PairAnalysis& a = pass.analyse(on, off);       // per pair
//   strobe_verdict(a.strobe, settings); a.blobs; a.noise.threshold(k, min); ...
//   if (overflow) pass.relabel(2 * a.threshold);          // at most kMaxRelabels per pair

#include <cstdint>
#include <optional>
#include <span>

#include "algo/core/image_view.hpp"
#include "algo/kernels/blob.hpp"
#include "algo/kernels/difference_noise.hpp"
#include "algo/kernels/fused_front_end.hpp"
#include "algo/kernels/run_labeller.hpp"
#include "algo/kernels/strobe_check.hpp"

namespace irloc {

struct PairPassConfig {
  FrontEndConfig front_end;  // frame size, pixel depth (value_bits), min_area, max_runs
  // The blobs' threshold: fixed_threshold when > 0, else noise.threshold(threshold_sigmas,
  // min_threshold) of the pair, grey levels.
  std::uint32_t fixed_threshold = 0;
  double threshold_sigmas = 5.0;
  std::uint32_t min_threshold = 6;
  int noise_rows = 48;         // rows read for the noise estimate
  int strobe_noise_level = 12;  // StrobeCheckSettings::noise_level
};

struct PairAnalysis {
  DifferenceNoise noise;         // of the pair's difference
  std::uint32_t threshold = 0;   // of the blobs below: foreground is on - off > threshold
  std::uint32_t relabels = 0;    // relabel() calls granted, this pair
  // Labelled first at the last pair's threshold, which was not this pair's own, and then again.
  bool labelled_twice = false;
  BlobList blobs;                // raster order of each blob's first pixel
  BlobCounters blob_counters;
  StrobeCounts strobe;           // counted by the first labelling, at the configured noise level
};

class PairPass {
 public:
  static constexpr std::uint32_t kMaxRelabels = 4;

  // Throws std::invalid_argument (at start-up) for a front-end configuration FusedFrontEnd refuses.
  explicit PairPass(const PairPassConfig& config);
  // Frames are referenced between analyse() and relabel(): it stays where it was made.
  PairPass(const PairPass&) = delete;
  PairPass& operator=(const PairPass&) = delete;

  // on, off: the pair, of one depth and the configured size. Allocates nothing.
  const PairAnalysis& analyse(const GrayImageView& on, const GrayImageView& off);
  // Labels the last analysed pair again at threshold (its frames must still be valid); strobe
  // counts and noise stay. false, and nothing changes, after kMaxRelabels relabellings of the pair.
  bool relabel(std::uint32_t threshold);

  const PairAnalysis& analysis() const { return analysis_; }
  // The foreground (on - off > analysis().threshold) of the last labelling as runs, raster order;
  // complete unless analysis().blob_counters.runs_dropped.
  std::span<const PixelRun> foreground_runs() const { return front_end_.runs(); }
  const PairPassConfig& config() const { return config_; }

 private:
  void label(bool count_strobe);
  void estimate_noise();  // analysis_.noise of the pair on_, off_

  PairPassConfig config_;
  DifferenceNoiseEstimator noise_;
  FusedFrontEnd front_end_;
  GrayImageView on_;
  GrayImageView off_;
  PairAnalysis analysis_;
  std::optional<std::uint32_t> last_threshold_;  // the last pair's, from its noise (unused when fixed)
};

}  // namespace irloc
