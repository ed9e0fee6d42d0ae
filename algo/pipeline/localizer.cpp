#include "algo/pipeline/localizer.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include <Eigen/Geometry>

#include "algo/pipeline/pose_fusion.hpp"
#include "algo/pipeline/pose_revision.hpp"
#include "algo/pipeline/source_registry.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc {
namespace {

void set_pose(const RigidTransform& world_from_base, const PoseCovariance& covariance, PoseEstimate& estimate) {
  const RollPitchYaw rpy = rpy_from_rotation(world_from_base.rotation);
  estimate.ok = true;
  estimate.x = world_from_base.translation.x();
  estimate.y = world_from_base.translation.y();
  estimate.z = world_from_base.translation.z();
  estimate.roll = rpy.roll;
  estimate.pitch = rpy.pitch;
  estimate.yaw = rpy.yaw;
  estimate.covariance = covariance;
}

// The shared pass labels its blobs with the dot source's threshold settings, because the dot
// source is the one that consumes them (any other threshold costs it a relabelling); the pixel
// depth is the camera's, which the config states in the dot section.
PairPassConfig pair_pass_config(const LocalizerSetup& setup) {
  PairPassConfig config;
  config.front_end.width = setup.camera.width;
  config.front_end.height = setup.camera.height;
  config.front_end.min_area = setup.dot.min_area;
  config.front_end.value_bits = setup.dot.pixel_bits;
  config.fixed_threshold = setup.dot.threshold;
  config.threshold_sigmas = setup.dot.threshold_sigmas;
  config.min_threshold = setup.dot.min_threshold;
  config.noise_rows = setup.dot.threshold_rows;
  config.strobe_noise_level = setup.strobe_check.noise_level;
  return config;
}

}  // namespace

Localizer::Localizer(LocalizerSetup setup)
    : setup_(std::move(setup)), pair_pass_(std::make_unique<PairPass>(pair_pass_config(setup_))) {
  sources_ = make_pose_sources(setup_, SourceSetup{setup_.camera, setup_.mount, setup_.dof, setup_.map, setup_.dot.pixel_bits});
  results_.resize(sources_.size());
}

void Localizer::restart() {
  last_pose_.reset();
  revisable_.reset();
  revised_previous_.reset();
  last_motion_.reset();
  strobe_verdict_.reset();
  for (const std::unique_ptr<PoseSource>& source : sources_) source->restart();
}

void Localizer::set_dot_markers(std::span<const DotMarker> markers) {
  setup_.map.dot_markers.assign(markers.begin(), markers.end());
}

bool Localizer::frames_fit(const StrobePair& pair) const {
  const auto fits = [&](const Frame& frame) {
    return width_of(frame.image) == setup_.camera.width && height_of(frame.image) == setup_.camera.height;
  };
  if (!fits(pair.on)) return false;
  return !pair.off || (fits(*pair.off) && pair.off->image.index() == pair.on.image.index());
}

void Localizer::remember_pose(const RigidTransform& world_from_base, bool plain, std::int64_t plain_delay_ns,
                              PoseEstimate& estimate) {
  last_motion_.reset();
  if (last_pose_ && !last_pose_->plain && !plain) {
    last_motion_ = motion_since(&*last_pose_, world_from_base, estimate.t_ns, kMaxTrackGapNs);
  }
  if (last_motion_) {
    // The motion is constant in the heading frame along the arc: at this pose, turned by its heading.
    PoseVelocity velocity;
    velocity.world = Eigen::AngleAxisd(estimate.yaw, Eigen::Vector3d::UnitZ()) * last_motion_->velocity;
    velocity.yaw_rate = last_motion_->yaw_rate;
    const double dt = static_cast<double>(estimate.t_ns - last_pose_->t_ns) * 1e-9;
    const PoseCovariance both = (last_pose_->covariance + estimate.covariance) / (dt * dt);
    constexpr int kYaw = 5;
    const std::array<int, 4> rows{0, 1, 2, kYaw};
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) velocity.covariance(i, j) = both(rows[i], rows[j]);
    }
    estimate.velocity = velocity;
    last_velocity_variance_ = both(0, 0) + both(1, 1);
    last_yaw_rate_variance_ = both(kYaw, kYaw);
  }
  last_pose_ = PosePrior{world_from_base, estimate.t_ns, plain, plain_delay_ns, estimate.covariance};
  estimate.revisable = plain;
  if (plain) revisable_ = estimate;
}

void Localizer::revise_previous(const PoseEstimate& previous, const SourceResult& only, const PoseEstimate& estimate) {
  const std::int64_t gap_ns = estimate.t_ns - previous.t_ns;
  if (!only.motion_from_track || !only.at_frame_time() || gap_ns <= 0 || gap_ns > kMaxTrackGapNs) return;
  PoseEstimate revised = previous;
  // The covariance stays the earlier pose's, and the revision must agree with it: the motion it is
  // taken back along (fitted to both frames' dots, or the arc between the two plain fits, each at
  // its mean row time) comes without a covariance of its own (on the rendered drives the revisions
  // of one dot marker's first poses are a tenth as far off as the first poses, a square's a
  // quarter: tests/sim/run/rolling_shutter_run_test.cpp).
  set_pose(pose_after(only.world_from_base, -static_cast<double>(gap_ns) * 1e-9, *only.motion_from_track),
           previous.covariance, revised);
  revised.revisable = false;
  if (revision_agrees(previous, revised, estimate.covariance)) revised_previous_ = revised;
}

SourceInput Localizer::source_input(const StrobePair& pair) const {
  SourceInput input{pair.on, pair.off ? &*pair.off : nullptr};
  if (last_pose_) input.prior = &*last_pose_;
  input.line_time_ns = pair.on.line_time_ns > 0 ? pair.on.line_time_ns : setup_.line_time_ns;
  input.limits = setup_.robot_limits;
  if (last_pose_ && last_motion_ && pair.on.t_ns >= last_pose_->t_ns) {
    const std::int64_t gap_ns = pair.on.t_ns - last_pose_->t_ns;
    if (gap_ns <= kMaxTrackGapNs) {
      input.motion = last_motion_;
      input.motion_velocity_variance = last_velocity_variance_;
      input.motion_yaw_rate_variance = last_yaw_rate_variance_;
    } else {
      input.motion_prior = motion_prior_after_gap(*last_motion_, last_velocity_variance_, last_yaw_rate_variance_,
                                                  static_cast<double>(gap_ns) * 1e-9, input.limits);
    }
  }
  return input;
}

PoseEstimate Localizer::process(const StrobePair& pair, StrobeGate gate) {
  stage_times_.clear();
  strobe_verdict_.reset();
  revised_previous_.reset();
  const std::optional<PoseEstimate> previous = std::exchange(revisable_, std::nullopt);
  PoseEstimate estimate;
  estimate.seq = pair.on.seq;
  estimate.t_ns = pair.on.t_ns;
  // A `none` row names the only source, or the first.
  estimate.source = sources_.empty() ? SourceKind::dot : sources_.front()->kind();
  if (!frames_fit(pair)) {
    ++bad_frames_;
    if (pair.off) strobe_verdict_ = StrobeVerdict::no_contrast;
    return estimate;
  }

  SourceInput input = source_input(pair);
  if (pair.off) {
    // The one pass over the pair that every source shares, and the strobe verdict from it.
    StageClock clock;
    clock.start(stage_times_);
    strobe_verdict_ = strobe_verdict(pair_pass_->analyse(pair.on.image, pair.off->image).strobe, setup_.strobe_check);
    clock.mark(stage_times_, "front_end");
    if (gate == StrobeGate::require_verified && *strobe_verdict_ != StrobeVerdict::verified) return estimate;
    input.pair = pair_pass_.get();
  }
  StaticVector<const SourceResult*, kMaxFusedSources> found;
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    SourceResult& result = results_[i];
    sources_[i]->process(input, result);
    for (const StageTime& stage : result.times) stage_times_.push_back(stage);
    if (result.ok) found.push_back(&result);
  }
  if (found.empty()) return estimate;

  const auto named = std::find_if(found.begin(), found.end(), [](const SourceResult* r) { return r->marker_id >= 0; });
  estimate.marker_id = named == found.end() ? -1 : (*named)->marker_id;
  if (found.size() == 1) {
    const SourceResult& only = *found[0];
    estimate.source = only.kind;
    estimate.confidence = only.confidence;
    set_pose(only.world_from_base, only.covariance, estimate);
    remember_pose(only.plain_fit.value_or(only.world_from_base), only.plain(), only.plain_delay_ns(), estimate);
    if (previous) revise_previous(*previous, only, estimate);
    return estimate;
  }
  // Several sources found a pose: their weighted mean, or none when they disagree.
  estimate.source = SourceKind::fused;
  FusedPose fused;
  if (!fuse_poses({found.begin(), found.size()}, setup_.dof, setup_.fusion, fused)) return estimate;
  for (const SourceResult* result : found) estimate.confidence = std::max(estimate.confidence, result->confidence);
  set_pose(fused.world_from_base, fused.covariance, estimate);
  bool plain = false;
  for (const SourceResult* result : found) plain = plain || result->plain();
  remember_pose(fused.world_from_base, plain, 0, estimate);
  return estimate;
}

}  // namespace irloc
