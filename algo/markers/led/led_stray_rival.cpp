// LedAssociator's decision on a searched minimal set (led_association.hpp): posed only when the
// search found no other association and no pose explains one LED fewer with a stray light.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "algo/markers/led/led_association.hpp"
#include "algo/markers/led/level_two_point.hpp"

namespace irloc::led {
namespace {

// The cells over the stray light's rivals: yaw under dof 3; roll and pitch under dof 6 (within
// max_tilt). A cell that an LED refutes throughout is done; another is halved down to the finest,
// where the pose at its centre decides.
constexpr double kRivalYawCell = 4 * std::numbers::pi / 180;  // radians
constexpr int kRivalTiltCells = 4;                              // each side of level
constexpr int kRivalHalvings = 5;

RigidTransform tilt_by(double roll, double pitch) {
  RigidTransform tilt;
  tilt.rotation = (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  return tilt;
}

}  // namespace

bool LedAssociator::minimal_set_decided(const LedAssociation& winner, const LedDetectionList& detections,
                                        const StaticVector<Eigen::Vector3d, kMaxLedDetections>& bearings) {
  // Another association of the detections (a dead LED among its predicted ones included) is a
  // verified pose beside the winner, or a hypothesis dropped for room, or one of detections the
  // search did not use.
  if (config_.max_rival_poses <= 0 || dof_ == Dof::height4 || verified_.size() != 1 || kept_dropped_ ||
      static_cast<int>(detections.size()) > config_.search_detections ||
      static_cast<int>(winner.matches.size()) != min_leds()) {
    return false;
  }
  RivalSearch rivals{winner, detections, bearings};
  // Rivals are common: the cells' centres first, then the cells halved until each is refuted.
  for (const int halvings : {0, kRivalHalvings}) {
    if (dof_ == Dof::full6 ? two_led_rival(rivals, halvings) : one_led_rival(rivals, halvings)) return false;
  }
  return true;
}

bool LedAssociator::one_led_rival(RivalSearch& rivals, int halvings) {
  // Level at height 0, the camera sees LED `led` along bearing d: its height fixes the range along
  // the bearing, and the yaw turns the camera round the LED on a circle of radius range x the
  // bearing's horizontal part.
  const Eigen::Vector3d& offset = base_from_camera_.translation;
  for (const Eigen::Vector3d& bearing : rivals.bearings) {
    if (bearing.squaredNorm() == 0) continue;
    const Eigen::Vector3d in_base = base_from_camera_.rotation * bearing;
    if (std::abs(in_base.z()) < 1e-9) continue;
    for (const LedLandmark& led : map_.led_landmarks) {
      const double range = (led.position.z() - offset.z()) / in_base.z();
      if (range <= 0 || range > config_.max_range) continue;
      const double radius = range * in_base.head<2>().norm();
      const auto pose_at = [&](double yaw) {
        RigidTransform pose;
        pose.rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        pose.translation = led.position - range * (pose.rotation * in_base) - pose.rotation * offset;
        return pose;
      };
      const auto in_cell = [&](auto& self, double yaw, double half, int depth) -> bool {
        if (++rivals.poses > config_.max_rival_poses) return true;
        const RigidTransform pose = pose_at(yaw);
        if (depth == 0) return stray_light_rival(pose, rivals, GridStep{}, true);
        if (!stray_light_rival(pose, rivals, {half, radius * half}, false)) return false;
        return self(self, yaw - half / 2, half / 2, depth - 1) || self(self, yaw + half / 2, half / 2, depth - 1);
      };
      for (double yaw = kRivalYawCell / 2; yaw < 2 * std::numbers::pi; yaw += kRivalYawCell) {
        if (in_cell(in_cell, yaw, kRivalYawCell / 2, halvings)) return true;
      }
    }
  }
  return false;
}

bool LedAssociator::two_led_rival(RivalSearch& rivals, int halvings) {
  // The base tilted by `tilt` (T_L_B, L the level frame under it): the camera's mount on L is
  // tilt x mount, so the level two-point form gives T_W_L for each tilt, and T_W_B = T_W_L x tilt.
  const auto& leds = map_.led_landmarks;
  const int m = static_cast<int>(leds.size());
  const double cell = config_.max_tilt / kRivalTiltCells;
  const auto& bearings = rivals.bearings;
  for (std::size_t j = 1; j < bearings.size(); ++j) {
    for (std::size_t i = 0; i < j; ++i) {
      if (bearings[i].squaredNorm() == 0 || bearings[j].squaredNorm() == 0) continue;
      for (int a = 0; a < m; ++a) {
        for (int b = 0; b < m; ++b) {
          if (a == b) continue;
          const std::array<Eigen::Vector3d, 2> pair = {leds[static_cast<std::size_t>(a)].position,
                                                       leds[static_cast<std::size_t>(b)].position};
          // A cell of roll and pitch within half of (roll, pitch): the base turns by at most
          // half x sqrt 2 about level axes, the yaw that keeps the pair on its bearings by as
          // much again, and the camera swings about the pair by that times its range (first order).
          const auto in_cell = [&](auto& self, double roll, double pitch, double half, int depth) -> bool {
            if (std::hypot(std::max(std::abs(roll) - half, 0.0), std::max(std::abs(pitch) - half, 0.0)) >
                config_.max_tilt) {
              return false;  // the whole cell tilts beyond max_tilt
            }
            if (++rivals.poses > config_.max_rival_poses) return true;
            const RigidTransform tilt = tilt_by(roll, pitch);
            LevelPoseSolutions solutions;
            solve_level_two_point(pair, {bearings[i], bearings[j]}, tilt * base_from_camera_, solutions);
            bool may_hold = false;
            for (const RigidTransform& level : solutions) {
              const RigidTransform pose = level * tilt;
              if (depth == 0) {
                if (stray_light_rival(pose, rivals, GridStep{}, true)) return true;
                continue;
              }
              const double turn = 2 * std::numbers::sqrt2 * half;
              const double lever = ((pose * base_from_camera_).translation - pair[0]).norm();
              may_hold = may_hold || stray_light_rival(pose, rivals, {turn, lever * turn}, false);
            }
            if (!may_hold) return false;
            const double quarter = half / 2;
            return self(self, roll - quarter, pitch - quarter, quarter, depth - 1) ||
                   self(self, roll - quarter, pitch + quarter, quarter, depth - 1) ||
                   self(self, roll + quarter, pitch - quarter, quarter, depth - 1) ||
                   self(self, roll + quarter, pitch + quarter, quarter, depth - 1);
          };
          for (int r = -kRivalTiltCells; r < kRivalTiltCells; ++r) {
            for (int p = -kRivalTiltCells; p < kRivalTiltCells; ++p) {
              if (in_cell(in_cell, (r + 0.5) * cell, (p + 0.5) * cell, cell / 2, halvings)) return true;
            }
          }
        }
      }
    }
  }
  return false;
}

bool LedAssociator::stray_light_rival(const RigidTransform& pose, const RivalSearch& rivals, const GridStep& step,
                                      bool finest) {
  if (!plausible_within(pose, step.turn, step.shift)) return false;
  if (finest && !distinct(pose, rivals.winner.fit.world_from_base)) return false;
  const RigidTransform world_from_camera = pose * base_from_camera_;
  if (config_.convex_room && behind_a_wall(world_from_camera.translation, step.shift)) return false;
  const LedDetectionList& detections = rivals.detections;
  std::fill(used_.begin(), used_.end(), 0);
  const RigidTransform camera_from_world = world_from_camera.inverse();
  const double gate2 = config_.search_gate_px * config_.search_gate_px;
  neighbourhood_.near(world_from_camera.translation, near_);
  unseen_.clear();
  int explained = 0;
  double faintest = std::numeric_limits<double>::infinity();
  for (const int l : near_) {
    const std::optional<PredictedLed> led =
        predict(l, pose, world_from_camera, camera_from_world, known_motion(), step.shift);
    if (!led) continue;
    double nearest2 = gate2;
    const int nearest = nearest_unused(led->pixel, detections, nearest2);
    if (nearest >= 0) {
      used_[static_cast<std::size_t>(nearest)] = 1;
      ++explained;
      faintest = std::min(faintest, detections[static_cast<std::size_t>(nearest)].brightness * led->range * led->range);
    } else if (led->must_be_seen &&
               well_inside(led->pixel, config_.edge_margin_px + grid_slack_px(l, camera_from_world, step))) {
      unseen_.push_back({l, led->range, in_glare(led->pixel)});
    }
  }
  // One LED fewer than the winner's, the rest left to a stray light; explaining every detection
  // the winner matched, it is another association of the minimal set: the search's.
  const auto& matches = rivals.winner.matches;
  if (finest && (explained < min_leds() - 1 || std::all_of(matches.begin(), matches.end(), [&](const LedMatch& match) {
                   return used_[static_cast<std::size_t>(match.detection)] != 0;
                 }))) {
    return false;
  }
  // One LED it predicts that must show refutes it.
  return std::none_of(unseen_.begin(), unseen_.end(), [&](const UnseenLed& led) {
    return !led.hidden && faintest / (led.range * led.range) >= config_.missing_brightness;
  });
}

bool LedAssociator::behind_a_wall(const Eigen::Vector3d& camera, double shift) const {
  // Behind the wall of LED l whatever its normal within cone_tolerance of the mapped axis: the
  // direction to the camera more than 90 degrees plus the tolerance off the axis, from anywhere
  // within `shift` of `camera` (the cell's reach).
  return std::any_of(map_.led_landmarks.begin(), map_.led_landmarks.end(), [&](const LedLandmark& led) {
    if (!led.direction) return false;
    const Eigen::Vector3d to_camera = camera - led.position;
    const double range = to_camera.norm();
    if (range <= shift) return false;
    const double off_axis = std::acos(std::clamp(led.direction->dot(to_camera) / range, -1.0, 1.0));
    return off_axis > std::numbers::pi / 2 + config_.cone_tolerance + std::asin(shift / range);
  });
}

double LedAssociator::grid_slack_px(int l, const RigidTransform& camera_from_world, const GridStep& step) const {
  // Within a cell the camera turns by at most step.turn and moves by at most step.shift: the
  // LED's direction from the camera turns by at most turn + shift / range, and its pixel moves by
  // at most that times the projection's rate there (the largest singular value of d pixel /
  // d point, times the range), to first order.
  if (step.turn == 0 && step.shift == 0) return 0;
  const Eigen::Vector3d point = camera_from_world * map_.led_landmarks[static_cast<std::size_t>(l)].position;
  Eigen::Vector2d pixel;
  Eigen::Matrix<double, 2, 3> jacobian;
  if (!camera_.project(point, pixel, jacobian)) return std::numeric_limits<double>::infinity();
  const double range = point.norm();
  const Eigen::Matrix2d gram = jacobian * jacobian.transpose();
  const double rate =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(gram, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff()) *
      range;
  return (step.turn + step.shift / range) * rate;
}

}  // namespace irloc::led
