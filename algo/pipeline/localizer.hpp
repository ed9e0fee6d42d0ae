#pragma once
// The per-frame pipeline: a strobe pair in, one pose attempt out. The same object runs in
// irlocd on the robot, in replay, and in irloc-sim.
//
// It checks the pair once (same depth, the calibrated size), runs the one shared pass over it
// (algo/kernels/pair_pass.hpp: noise estimate, blobs, strobe counts) and gives the strobe verdict,
// hands both to every pose source the setup makes (source_registry.hpp), and builds the attempt's
// PoseEstimate: the one source that found a pose, or the covariance-weighted fusion of several
// (source `fused`), or none.

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "algo/frames/stage_times.hpp"
#include "algo/frames/strobe_pairer.hpp"
#include "algo/kernels/pair_pass.hpp"
#include "algo/kernels/strobe_check.hpp"
#include "algo/pipeline/localizer_setup.hpp"
#include "algo/pipeline/pose_estimate.hpp"
#include "algo/source/pose_source.hpp"
#include "algo/source/source_input.hpp"

namespace irloc {

inline constexpr std::size_t kMaxFusedSources = 8;

// What a failed strobe verdict does to a pose attempt.
enum class StrobeGate {
  report,            // the verdict is only reported (replay: the dataset's labels are trusted)
  require_verified,  // a pair that is not `verified` gives none without running the sources (live strobing)
};

class Localizer {
 public:
  // Makes the sources and allocates every buffer the per-frame path needs; process() allocates
  // nothing. Throws std::invalid_argument for a map or config a source cannot use.
  explicit Localizer(LocalizerSetup setup);

  // One pose attempt for the pair's LED-on frame. A pair whose frames are not of the calibrated
  // size, or differ in depth, gives none (and counts in bad_frames()); so does, with
  // StrobeGate::require_verified, a pair whose strobe verdict is not `verified`.
  PoseEstimate process(const StrobePair& pair, StrobeGate gate = StrobeGate::report);
  // Forgets every earlier pair: the last pose and motion, and each source's tracks and
  // backgrounds (PoseSource::restart), so that the next process() gives what a Localizer just
  // made would give. The map (as set_dot_markers left it) and bad_frames() stay. Allocates nothing.
  void restart();

  // After process(): the attempt before it once more, where that pose was `revisable` and this
  // attempt's (one source, at its frame's t_ns, at most kMaxTrackGapNs later) came with the motion
  // between the two frames (SourceResult::motion_from_track: fitted to both frames' points, or the
  // arc between their plain fits): this pose taken back along that motion to the earlier t_ns,
  // where that agrees with the earlier pose's covariance (pose_revision.hpp). Empty otherwise.
  const std::optional<PoseEstimate>& revised_previous() const { return revised_previous_; }

  const LocalizerSetup& setup() const { return setup_; }
  // Map building (docs/survey.md): the dot markers to localize with, as a survey has established
  // them, replace the map's (a marker left out gives no pose). The sources read the map in place,
  // so the next attempt uses them. Between attempts; allocates when the set outgrows the map.
  void set_dot_markers(std::span<const DotMarker> markers);
  // Per-stage wall-clock times of the last process(), every source's in turn.
  const StageClock::Times& last_stage_times() const { return stage_times_; }
  // The sources, and each one's result for the last pair (same order).
  std::span<const std::unique_ptr<PoseSource>> sources() const { return sources_; }
  std::span<const SourceResult> last_results() const { return results_; }
  std::uint64_t bad_frames() const { return bad_frames_; }
  // The strobe verdict of the last pair: empty without an LED-off frame; no_contrast for frames
  // that do not fit.
  std::optional<StrobeVerdict> last_strobe_verdict() const { return strobe_verdict_; }
  // The shared pass over the last pair (valid when last_strobe_verdict() came from it).
  const PairAnalysis& last_pair_analysis() const { return pair_pass_->analysis(); }

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
  // What the sources are given of the pair beside its frames: the last pose as the prior, the
  // line time, the robot's limits, and the track's motion (within kMaxTrackGapNs of the last pose)
  // or, after a longer gap, the motion before it as the prior of the frame's own motion fit.
  SourceInput source_input(const StrobePair& pair) const;
  // Keeps the attempt's pose as the next prior and, with the pose before it, the track's motion
  // (only from two poses at their frames' t_ns: a plain fit, `plain`, is biased by its frame's
  // motion), which it also gives the estimate as its velocity; a plain one is also `revisable`,
  // kept for the next attempt to revise.
  // plain_delay_ns: how long after t_ns the plain fit holds (SourceResult::plain_delay_ns; 0 for
  // a fused pose).
  void remember_pose(const RigidTransform& world_from_base, bool plain, std::int64_t plain_delay_ns,
                     PoseEstimate& estimate);
  // revised_previous() from the revisable estimate before this attempt's pose (found by `only`).
  void revise_previous(const PoseEstimate& previous, const SourceResult& only, const PoseEstimate& estimate);

  LocalizerSetup setup_;
  std::optional<PosePrior> last_pose_;  // handed to the sources as SourceInput::prior
  std::optional<FrameMotion> last_motion_;  // from last_pose_ and the pose before it
  // last_motion_'s variances: of a velocity axis (m/s)^2 (at most the x-y block's trace) and of the
  // yaw rate (rad/s)^2, from the two poses' covariances.
  double last_velocity_variance_ = 0, last_yaw_rate_variance_ = 0;
  std::optional<PoseEstimate> revisable_;  // the last attempt's estimate, where it was revisable
  std::optional<PoseEstimate> revised_previous_;
  std::vector<std::unique_ptr<PoseSource>> sources_;
  std::vector<SourceResult> results_;  // one per source
  std::unique_ptr<PairPass> pair_pass_;
  std::optional<StrobeVerdict> strobe_verdict_;
  StageClock::Times stage_times_;
  std::uint64_t bad_frames_ = 0;
};

}  // namespace irloc
