#pragma once
// The outside-in pose source (SourceKind::external): a fixed camera watches the floor and finds
// the robot, a box of known size, in it. Per frame: adaptive background and foreground
// (adaptive_background.hpp), opening and closing, connected components, a box fit to each
// plausible blob (box_silhouette.hpp), then a constant-velocity track that chooses the robot's
// blob, resolves the box's 180-degree heading ambiguity from the robot's travel and keeps the
// robot through a few frames of occlusion. A pose only for a blob the box explains: people and
// other movers give none. Where the foreground shows a robot only in part (faces as bright as the
// floor), the box is fitted to the pixels themselves (appearance_fit.hpp). SourceInput.off is not
// used (a camera without a strobe).
#include <array>
#include <memory>
#include <span>
#include <vector>
#include "algo/geometry/camera_model.hpp"
#include "algo/kernels/blob_labeller.hpp"
#include "algo/markers/outside_in/appearance_fit.hpp"
#include "algo/markers/outside_in/end_face_looks.hpp"
#include "algo/markers/outside_in/frame_period.hpp"
#include "algo/markers/outside_in/heading_filter.hpp"
#include "algo/markers/outside_in/open_and_close.hpp"
#include "algo/markers/outside_in/outside_in_config.hpp"
#include "algo/markers/outside_in/outside_in_outcome.hpp"
#include "algo/markers/outside_in/travel_branch.hpp"
#include "algo/source/pose_source.hpp"

namespace irloc::outside_in {

// The track's last fitted positions, for its direction of travel (a fixed ring: no allocation).
struct TravelHistory {
  static constexpr int kCapacity = 32;  // 1 s at 30 fps
  struct Point {
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
    std::int64_t t_ns = 0;
  };
  void add(const Eigen::Vector2d& position, std::int64_t t_ns) {
    next_ = (next_ + 1) % kCapacity;
    points_[static_cast<std::size_t>(next_)] = {position, t_ns};
    if (size_ < kCapacity) ++size_;
  }
  // Forgets the newest point (none when empty).
  void drop_newest() {
    if (size_ == 0) return;
    next_ = (next_ - 1 + kCapacity) % kCapacity;
    --size_;
  }
  // The k-th newest point (0: the newest), k < size().
  const Point& back(int k) const { return points_[static_cast<std::size_t>((next_ - k + kCapacity) % kCapacity)]; }
  int size() const { return size_; }

 private:
  std::array<Point, kCapacity> points_{};
  int next_ = 0, size_ = 0;
};

// What lay behind the last pose attempt's outcome (benchmarks rank the causes of missed poses).
struct AttemptDetail {
  int dropped_extent_px = 0;          // the chosen fit's blob short of the robot (dropped_foreground.hpp)
  double filter_heading_sigma = 0;    // rad: the heading filter's
  double camera_heading_sigma = 0;    // rad: the floor reference's part at the fit's view
  int track_frames = 0;               // frames with a fit since the track began (1: it began now)
  double track_yaw = 0;               // rad: the track's heading, posed or not
};

class OutsideInSource final : public PoseSource {
 public:
  // Allocates every buffer. Throws std::invalid_argument with the floor_reference check that
  // failed (floor_geometry.hpp).
  OutsideInSource(const SourceSetup& setup, const OutsideInConfig& config);

  SourceKind kind() const override { return SourceKind::external; }
  void process(const SourceInput& input, SourceResult& result) override;
  // Forgets the background, the track and where the robot was last seen.
  void restart() override;

  const FloorGeometry& floor() const { return floor_; }
  // What the last process() saw: its background step (light change, foreground pixels).
  const BackgroundStep& last_diagnostics() const { return background_step_; }
  ImageView8 foreground() const { return {mask_.data(), width_, height_}; }
  const AttemptDetail& last_attempt() const { return attempt_; }

 private:
  struct Track {
    bool active = false;
    bool heading_known = false;
    bool moved = false;               // it has driven: the robot, not what was behind it at start-up
    FloorPose pose;                   // yaw in (-pi, pi] once heading_known, else [0, symmetry turn)
    Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // m/s
    HeadingFilter heading;            // pose.yaw is its yaw (modulo the symmetry turn until heading_known)
    Eigen::Vector2d anchor = Eigen::Vector2d::Zero();    // where the track began
    Eigen::Vector2d moved_from = Eigen::Vector2d::Zero();  // where its travel was last counted
    std::int64_t t_ns = 0;
    std::int64_t start_t_ns = 0;      // when it began
    std::int64_t heading_t_ns = 0;    // when a fit last measured the heading
    double heading_sigma = 0;         // rad: the heading's sigma then
    int missed = 0;                   // frames without a fit since the last one
    int frames = 0;                   // frames with a fit since the track began
    bool beside_merge = false;        // the last frame gave it no fit the box explains
    bool branch_from_travel = false;  // an appearance fit began it: no pose before `branch` is confirmed
    TravelBranch branch;
    int end_votes = 0;                // views in a row telling the branch by the end faces: + kept, - turned
    Silhouette silhouette;
    TravelHistory travel;
  };

  // The robot's last pose with a known heading and its velocity then, for a new track within 2 s
  // and 1 m of where it would be had it kept that velocity.
  struct LastSeen {
    bool valid = false;
    FloorPose pose;
    double heading_sigma = 0;  // rad, the filter's then
    Eigen::Vector2d velocity = Eigen::Vector2d::Zero();  // m/s
    std::int64_t t_ns = 0;
    Eigen::Vector2d expected_at(std::int64_t t) const {
      return Eigen::Vector2d(pose.x, pose.y) + velocity * (static_cast<double>(t - t_ns) * 1e-9);
    }
  };

  // A frame's fits so far, against their bounds (config max_fits_per_frame, kMaxAppearanceFits).
  struct FitCount {
    int fits = 0;
    int appearance_fits = 0;
  };
  // The box fitted to a blob of a plausible area for the box at its place (counted), when the fit
  // passes the shape check (step 4 of docs/outside_in.md), or the appearance fit from it where the
  // blob may be part of the robot (by_appearance).
  // `predicted`, `heading`: the live track's prediction for this frame (choose_fit).
  bool fit_blob(const Blob& blob, const Eigen::Vector2d& predicted, const HeadingPrior& heading, std::int64_t t_ns,
                FitCount& count, BoxFit& fit, bool& by_appearance, EndView& end) const;
  // The appearance fit from `starts`, when it explains the robot at a heading the robot can have
  // turned to (reachable_heading), as a BoxFit: its pose, with the silhouette fit of the box's
  // outline there (the shape and covariance a whole blob would give), and the end face it saw
  // (its side at the fit's yaw).
  bool fit_by_appearance(std::span<const FloorPose> starts, const HeadingPrior& heading, std::int64_t t_ns,
                         BoxFit& fit, EndView& end) const;
  // Whether a heading (modulo the symmetry turn) is one the live track's robot can have turned to
  // since its last fit: the config's yaw rate, 3 sigma of its filter and kTurnSlackRad.
  bool reachable_heading(double yaw, std::int64_t t_ns) const;
  // Whether a blob's fit at `pose` can carry the live track predicted at `predicted`: always but when
  // the track knows its heading, where only the gated continuation is a candidate (choose_fit) and a
  // blob farther than the gate and an appearance fit's reach is not worth that fit.
  bool may_carry_track(const FloorPose& pose, const Eigen::Vector2d& predicted) const;
  // The fit taken for the robot this frame, and what is known of its blob.
  struct ChosenFit {
    BoxFit fit;
    bool continues_track = false;  // the live track's, else it starts a new one
    bool explained = false;        // the box explains its blob (else no pose, step 4 of docs/outside_in.md)
    int dropped_extent = 0;        // px the blob may be short of the robot (dropped_foreground.hpp)
    bool by_appearance = false;    // the appearance fit's (appearance_fit.hpp)
    EndView end;                   // the end face that fit saw, at fit.pose.yaw
  };
  // False when no blob is the robot's.
  bool choose_fit(std::int64_t t_ns, ChosenFit& chosen) const;
  // No blob carries the live track: the appearance fit from where the track predicts the robot,
  // within the track's gate and whole in view.
  bool fit_at_prediction(std::int64_t t_ns, const Eigen::Vector2d& predicted, const HeadingPrior& heading,
                         ChosenFit& chosen) const;
  OutsideInOutcome update_track(std::int64_t t_ns, const ChosenFit& chosen, const MotionLimits& limits);
  // The end face a fit saw: learned as the front or back where the track's heading is `confident`
  // and its branch known; else a vote on the branch, which kEndVotes votes in a row decide.
  void use_end_view(const EndView& end, double fit_yaw, bool confident);
  // A frame where the track's blob is not the box alone (not explained, or no fit): its fits next
  // to it in time are no points of the travel.
  void mark_merge();
  // The foreground before the cleaning (the mask the fit sees is foreground()).
  ImageView8 foreground_view() const { return {foreground_.data(), width_, height_}; }
  void start_track(std::int64_t t_ns, const ChosenFit& chosen, double white_variance, double bias_variance,
                   const MotionLimits& limits);
  void measure_heading(std::int64_t t_ns, const BoxFit& fit, double white_variance, double bias_variance,
                       bool adds_travel, const MotionLimits& limits);
  // The heading from the direction of travel (modulo a half turn: the robot may reverse), when it
  // drove far enough within the last second for it to tell.
  void update_heading_from_travel();
  // Under a rolling shutter: the fit moved to the frame's time t_ns by the track's motion; false
  // when the motion is not known (a new track).
  bool fit_at_frame_time(std::int64_t t_ns, std::int64_t line_time_ns, bool continues_track, BoxFit& fit) const;
  void forget_if_clock_broke(std::int64_t t_ns);
  void fill_result(const ChosenFit& chosen, bool motion_known, const SourceInput& input, SourceResult& result) const;
  bool touches_border(int x_min, int y_min, int x_max, int y_max) const;
  ProtectedRects protected_rects(std::int64_t t_ns) const;

  OutsideInConfig config_;
  int width_, height_;
  CameraModel camera_;
  FloorGeometry floor_;
  BoxSilhouette box_;
  AppearanceFitter appearance_;
  EndFaceLooks end_looks_;
  AdaptiveBackground background_;
  BackgroundStep background_step_;
  FramePeriod frame_period_;
  OpenAndClose open_and_close_;
  BlobLabeller labeller_;
  std::vector<std::uint8_t> foreground_, scratch_, mask_;
  BlobList blobs_;
  Track track_;
  LastSeen last_seen_;
  AttemptDetail attempt_;
  StageClock clock_;
  // The frame being processed and the robot's motion limits (valid within process()).
  ImageView8 frame_{};
  MotionLimits limits_;
};

}  // namespace irloc::outside_in
