#pragma once
// The per-frame pipeline: a strobe pair in, one pose attempt out. The same object runs in
// irlocd on the robot, in replay, and in irloc-sim.
//
// It checks the pair once (same depth, the calibrated size), hands it to every pose source the
// setup makes (source_registry.hpp), and builds the attempt's PoseEstimate: the one source that
// found a pose, or the covariance-weighted fusion of several (source `fused`), or none.

#include <memory>
#include <span>
#include <vector>

#include "algo/frames/stage_times.hpp"
#include "algo/frames/strobe_pairer.hpp"
#include "algo/pipeline/localizer_setup.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "algo/source/pose_source.hpp"

namespace irloc {

inline constexpr std::size_t kMaxFusedSources = 8;

class Localizer {
 public:
  // Makes the sources and allocates every buffer the per-frame path needs; process() allocates
  // nothing. Throws std::invalid_argument for a map or config a source cannot use.
  explicit Localizer(LocalizerSetup setup);

  // One pose attempt for the pair's LED-on frame. A pair whose frames are not of the calibrated
  // size, or differ in depth, gives none (and counts in bad_frames()).
  PoseEstimate process(const StrobePair& pair);

  const LocalizerSetup& setup() const { return setup_; }
  // Per-stage wall-clock times of the last process(), every source's in turn.
  const StageClock::Times& last_stage_times() const { return stage_times_; }
  // The sources, and each one's result for the last pair (same order).
  std::span<const std::unique_ptr<PoseSource>> sources() const { return sources_; }
  std::span<const SourceResult> last_results() const { return results_; }
  std::uint64_t bad_frames() const { return bad_frames_; }

  // The source of type Source, or nullptr when the setup made none.
  template <typename Source>
  const Source* find_source() const {
    for (const std::unique_ptr<PoseSource>& source : sources_) {
      if (const auto* found = dynamic_cast<const Source*>(source.get())) return found;
    }
    return nullptr;
  }

 private:
  bool frames_fit(const StrobePair& pair) const;

  LocalizerSetup setup_;
  std::vector<std::unique_ptr<PoseSource>> sources_;
  std::vector<SourceResult> results_;  // one per source
  StageClock::Times stage_times_;
  std::uint64_t bad_frames_ = 0;
};

}  // namespace irloc
