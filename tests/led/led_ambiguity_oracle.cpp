#include "tests/led/led_ambiguity_oracle.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "algo/geometry/p3p.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/markers/led/level_two_point.hpp"

namespace irloc::test {

AmbiguityOracle::AmbiguityOracle(const sim::LedFamilyScene& scene, const led::LedSourceConfig& config)
    : scene_(scene), camera_(scene.camera), config_(config) {
  for (std::size_t k = 0; k < scene.leds.size(); ++k) {
    if (k >= scene.dead.size() || !scene.dead[k]) installed_lit_.push_back(scene.leds[k]);
  }
}

bool AmbiguityOracle::ambiguous(const RigidTransform& truth, const sim::LedFamilyPair& pair) const {
  std::vector<Eigen::Vector2d> points;
  for (const sim::VisibleLed& led : pair.visible) points.push_back(led.pixel);
  points.insert(points.end(), pair.stray.begin(), pair.stray.end());
  const int n = static_cast<int>(points.size());
  const int k = scene_.dof == Dof::full6 ? 3 : 2;
  const int truth_explained = explained(mapped(), truth, points);
  const int truth_unseen = unseen(mapped(), truth, points);
  if (truth_explained < k) return false;
  // Every k-subset of the first n - truth_explained + k points, in lexicographic order.
  const int first = std::min(n, n - truth_explained + k);
  std::array<int, 3> subset{0, 1, 2};
  while (true) {
    if (any_rival_from(std::span<const int>(subset.data(), static_cast<std::size_t>(k)), truth, points,
                       truth_explained, truth_unseen)) {
      return true;
    }
    int i = k - 1;
    while (i >= 0 && subset[static_cast<std::size_t>(i)] == first - k + i) --i;
    if (i < 0) return false;
    ++subset[static_cast<std::size_t>(i)];
    for (int j = i + 1; j < k; ++j) subset[static_cast<std::size_t>(j)] = subset[static_cast<std::size_t>(j - 1)] + 1;
  }
}

std::optional<RigidTransform> AmbiguityOracle::stray_light_rival(
    const RigidTransform& truth, const sim::LedFamilyPair& pair, RivalAxes axes,
    const std::function<bool(const RigidTransform&)>& shows) const {
  std::vector<Eigen::Vector2d> points;
  for (const sim::VisibleLed& led : pair.visible) points.push_back(led.pixel);
  points.insert(points.end(), pair.stray.begin(), pair.stray.end());
  const int n = static_cast<int>(points.size());
  const int k = scene_.dof == Dof::full6 ? 3 : 2;
  if (explained(mapped(), truth, points) != k) return std::nullopt;
  std::vector<Eigen::Vector2d> truth_points;  // the minimal set the truth explains
  for (const Eigen::Vector2d& point : points) {
    if (explained(mapped(), truth, std::span<const Eigen::Vector2d>(&point, 1)) == 1) truth_points.push_back(point);
  }
  const auto is_rival = [&](const RigidTransform& pose) {
    return robust_stray_light_rival(pose, truth, points, truth_points, axes) && (!shows || shows(pose));
  };
  const auto& leds = scene_.map.led_landmarks;
  const int m = static_cast<int>(leds.size());
  std::vector<Eigen::Vector3d> bearings(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) camera_.unproject(points[i], bearings[i]);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < m; ++a) {
      if (k == 2) {
        if (auto found = one_point_rival(leds[a].position, bearings[i], is_rival)) return found;
        continue;
      }
      for (int j = i + 1; j < n; ++j) {
        for (int b = 0; b < m; ++b) {
          if (b == a) continue;
          if (auto found = two_point_rival({leds[a].position, leds[b].position}, {bearings[i], bearings[j]}, is_rival)) {
            return found;
          }
        }
      }
    }
  }
  return std::nullopt;
}

template <typename IsRival>
std::optional<RigidTransform> AmbiguityOracle::one_point_rival(const Eigen::Vector3d& led, const Eigen::Vector3d& bearing,
                                                               const IsRival& is_rival) const {
  // Level base: the bearing's height component in B is the same in W whatever the yaw, so the
  // base's height fixes the range along the bearing, and the yaw turns the camera round the LED.
  const Eigen::Vector3d in_base = scene_.mount.rotation * bearing;
  const Eigen::Vector3d& offset = scene_.mount.translation;
  const auto height_at = [&](double range) { return led.z() - offset.z() - range * in_base.z(); };
  std::vector<double> ranges;
  const auto add_range_at_height = [&](double height) {
    if (std::abs(in_base.z()) > 1e-9) ranges.push_back((led.z() - offset.z() - height) / in_base.z());
  };
  if (scene_.dof == Dof::planar3) {
    add_range_at_height(0);
  } else {
    for (double height = config_.min_height; height <= config_.max_height + 1e-9; height += kRivalHeightStep) {
      add_range_at_height(height);
    }
    for (int step = 0; step <= kRivalRanges; ++step) {
      const double range = kRivalMinRange * std::pow(config_.max_range / kRivalMinRange, double(step) / kRivalRanges);
      if (height_at(range) >= config_.min_height && height_at(range) <= config_.max_height) ranges.push_back(range);
    }
  }
  for (const double range : ranges) {
    if (range <= 0 || range > config_.max_range) continue;
    for (double yaw = 0; yaw < 2 * std::numbers::pi; yaw += kRivalYawStep) {
      RigidTransform pose;
      pose.rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Vector3d camera = led - range * (pose.rotation * in_base);
      pose.translation = camera - pose.rotation * offset;
      if (is_rival(pose)) return pose;
    }
  }
  return std::nullopt;
}

template <typename IsRival>
std::optional<RigidTransform> AmbiguityOracle::two_point_rival(const std::array<Eigen::Vector3d, 2>& leds,
                                                               const std::array<Eigen::Vector3d, 2>& bearings,
                                                               const IsRival& is_rival) const {
  // Base tilted by `tilt` (T_L_B, L the level frame under it): the camera's mount on L is
  // tilt x mount, so the level two-point closed form gives T_W_L, and T_W_B = T_W_L x tilt.
  const double step = config_.max_tilt / kRivalTiltSteps;
  for (int r = -kRivalTiltSteps; r <= kRivalTiltSteps; ++r) {
    for (int p = -kRivalTiltSteps; p <= kRivalTiltSteps; ++p) {
      RigidTransform tilt;
      tilt.rotation = (Eigen::AngleAxisd(p * step, Eigen::Vector3d::UnitY()) *
                       Eigen::AngleAxisd(r * step, Eigen::Vector3d::UnitX())).toRotationMatrix();
      if (std::acos(std::clamp(tilt.rotation(2, 2), -1.0, 1.0)) > config_.max_tilt) continue;
      led::LevelPoseSolutions solutions;
      led::solve_level_two_point(leds, bearings, tilt * scene_.mount, solutions);
      for (const RigidTransform& level : solutions) {
        if (is_rival(level * tilt)) return level * tilt;
      }
    }
  }
  return std::nullopt;
}

bool AmbiguityOracle::any_rival_from(std::span<const int> subset, const RigidTransform& truth,
                                     std::span<const Eigen::Vector2d> points, int truth_explained,
                                     int truth_unseen) const {
  const auto& leds = scene_.map.led_landmarks;
  const int m = static_cast<int>(leds.size());
  std::array<Eigen::Vector3d, 3> bearings;
  for (std::size_t s = 0; s < subset.size(); ++s) {
    camera_.unproject(points[static_cast<std::size_t>(subset[s])], bearings[s]);
  }
  auto is_rival = [&](const RigidTransform& pose) {
    RigidTransform refined_pose;
    return rival(pose, truth, points, truth_explained, truth_unseen) ||
           (refined(pose, points, truth_explained, refined_pose) &&
            rival(refined_pose, truth, points, truth_explained, truth_unseen));
  };
  const RigidTransform camera_from_base = scene_.mount.inverse();
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      if (a == b) continue;
      if (subset.size() == 2) {
        led::LevelPoseSolutions solutions;
        led::solve_level_two_point({leds[a].position, leds[b].position}, {bearings[0], bearings[1]}, scene_.mount,
                                   solutions);
        if (std::any_of(solutions.begin(), solutions.end(), is_rival)) return true;
        continue;
      }
      for (int c = 0; c < m; ++c) {
        if (c == a || c == b) continue;
        P3PSolutions solutions;
        solve_p3p({leds[a].position, leds[b].position, leds[c].position}, {bearings[0], bearings[1], bearings[2]},
                  solutions);
        for (const RigidTransform& camera_from_world : solutions) {
          if (is_rival(camera_from_world.inverse() * camera_from_base)) return true;
        }
      }
    }
  }
  return false;
}

bool AmbiguityOracle::refined(const RigidTransform& pose, std::span<const Eigen::Vector2d> points, int truth_explained,
                              RigidTransform& refined_pose) const {
  const RigidTransform world_from_camera = pose * scene_.mount;
  const RigidTransform camera_from_world = world_from_camera.inverse();
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  for (const Eigen::Vector2d& point : points) {
    for (const LedLandmark& led : scene_.map.led_landmarks) {
      Eigen::Vector2d pixel;
      if (may_emit_toward(led, world_from_camera.translation, kAxisTolerance) &&
          camera_.project(camera_from_world * led.position, pixel) && (pixel - point).norm() < kNearPx) {
        world.push_back(led.position);
        pixels.push_back(point);
        break;
      }
    }
  }
  if (static_cast<int>(world.size()) < truth_explained) return false;
  RefinementOptions options;
  options.dof = scene_.dof;
  options.loss_scale_px = config_.loss_scale_px;
  options.pixel_sigma = config_.pixel_sigma;
  const PoseFit fit = refine_pose(world, pixels, camera_, scene_.mount, pose, options);
  refined_pose = fit.world_from_base;
  return fit.ok;
}

bool AmbiguityOracle::rival(const RigidTransform& pose, const RigidTransform& truth,
                            std::span<const Eigen::Vector2d> points, int truth_explained, int truth_unseen) const {
  const bool distinct =
      (pose.translation - truth.translation).norm() > kDistinctPosition ||
      Eigen::AngleAxisd(pose.rotation.transpose() * truth.rotation).angle() > kDistinctAngle;
  return distinct && plausible(pose) && explained(mapped(), pose, points) >= truth_explained &&
         unseen(mapped(), pose, points) <= truth_unseen;
}

bool AmbiguityOracle::plausible(const RigidTransform& pose) const {
  const double z = pose.translation.z();
  if (scene_.dof == Dof::planar3) return std::abs(z) < kDistinctPosition;
  if (z < config_.min_height || z > config_.max_height) return false;
  return std::acos(std::clamp(pose.rotation(2, 2), -1.0, 1.0)) <= config_.max_tilt;
}

// Whether the camera at `camera` (W) lies inside the mapped LED's cone widened by `widen` radians
// (negative: narrowed); an LED without a cone emits everywhere.
bool AmbiguityOracle::may_emit_toward(const LedLandmark& mapped, const Eigen::Vector3d& camera, double widen) const {
  if (!mapped.direction || !mapped.half_angle) return true;
  const double half_angle = std::clamp(*mapped.half_angle + widen, 0.0, std::numbers::pi);
  return mapped.direction->dot((camera - mapped.position).normalized()) >= std::cos(half_angle);
}

bool AmbiguityOracle::robust_stray_light_rival(const RigidTransform& pose, const RigidTransform& truth,
                                               std::span<const Eigen::Vector2d> points,
                                               std::span<const Eigen::Vector2d> truth_points,
                                               RivalAxes axes) const {
  const int k = static_cast<int>(truth_points.size());
  const bool distinct =
      (pose.translation - truth.translation).norm() > kDistinctPosition ||
      Eigen::AngleAxisd(pose.rotation.transpose() * truth.rotation).angle() > kDistinctAngle;
  // Its k - 1 LEDs surely emit toward it (for some axes: may); one of the truth's points is left to
  // a stray light (explaining all k, it is a rival of ambiguous()); no other LED that may emit (for
  // some axes: that surely emits) shows anywhere in the image, even where the truth leaves LEDs
  // unseen (too dim there, they may show at the rival).
  // And the camera is in the room: in front of every mapped LED's mounting surface (the plane
  // through it across its mapped axis, the surface's normal); the family's rooms are convex.
  const Eigen::Vector3d camera = (pose * scene_.mount).translation;
  const bool in_room =
      std::all_of(scene_.map.led_landmarks.begin(), scene_.map.led_landmarks.end(), [&](const LedLandmark& led) {
        return !led.direction || led.direction->dot(camera - led.position) > 0;
      });
  if (!distinct || !in_room || !plausible(pose) || explained(mapped(), pose, truth_points) >= k) return false;
  // For some axes: its LEDs inside their cones widened, every other LED in the image outside its
  // cone narrowed. For the installed axes: their own cones, a dead LED dark.
  if (axes == RivalAxes::installed) {
    return explained(installed_lit_, pose, points, 0) >= k - 1 && unseen(installed_lit_, pose, points, 0, 0) == 0;
  }
  const double doubt = axes == RivalAxes::every ? kAxisTolerance : -kAxisTolerance;
  return explained(mapped(), pose, points, -doubt) >= k - 1 && unseen(mapped(), pose, points, doubt, 0) == 0;
}

int AmbiguityOracle::explained(std::span<const LedLandmark> leds, const RigidTransform& pose,
                               std::span<const Eigen::Vector2d> points, double widen) const {
  const RigidTransform world_from_camera = pose * scene_.mount;
  const RigidTransform camera_from_world = world_from_camera.inverse();
  return static_cast<int>(std::count_if(points.begin(), points.end(), [&](const Eigen::Vector2d& point) {
    return std::any_of(leds.begin(), leds.end(), [&](const LedLandmark& led) {
      Eigen::Vector2d pixel;
      return may_emit_toward(led, world_from_camera.translation, widen) &&
             camera_.project(camera_from_world * led.position, pixel) && (pixel - point).norm() < kExplainsPx;
    });
  }));
}

int AmbiguityOracle::unseen(std::span<const LedLandmark> leds, const RigidTransform& pose,
                            std::span<const Eigen::Vector2d> points, double widen, double margin) const {
  const RigidTransform world_from_camera = pose * scene_.mount;
  const RigidTransform camera_from_world = world_from_camera.inverse();
  if (margin < 0) margin = config_.edge_margin_px;
  int count = 0;
  for (const LedLandmark& led : leds) {
    Eigen::Vector2d pixel;
    if (!may_emit_toward(led, world_from_camera.translation, widen) ||
        !camera_.project(camera_from_world * led.position, pixel) || pixel.x() < margin || pixel.y() < margin ||
        pixel.x() > scene_.camera.width - 1 - margin || pixel.y() > scene_.camera.height - 1 - margin) {
      continue;
    }
    count += std::none_of(points.begin(), points.end(),
                          [&](const Eigen::Vector2d& point) { return (point - pixel).norm() < kExplainsPx; });
  }
  return count;
}

bool renderer_shows_stray_light_rival(const sim::LedFamilyScene& scene, int attempt, const RigidTransform& rival,
                                      const sim::LedFamilyPair& pair, double threshold, sim::LedFamilyPair& at_rival) {
  sim::render_led_family_pair_at(scene, attempt, rival, threshold, at_rival);
  const auto on_a_point = [&](const sim::VisibleLed& led) {
    const auto near = [&](const Eigen::Vector2d& point) {
      return (point - led.pixel).norm() < AmbiguityOracle::kExplainsPx;
    };
    return std::any_of(pair.visible.begin(), pair.visible.end(),
                       [&](const sim::VisibleLed& seen) { return near(seen.pixel); }) ||
           std::any_of(pair.stray.begin(), pair.stray.end(), near);
  };
  const std::size_t minimal_less_one = scene.dof == Dof::full6 ? 2 : 1;
  return at_rival.visible.size() == minimal_less_one &&
         std::all_of(at_rival.visible.begin(), at_rival.visible.end(), on_a_point);
}

}  // namespace irloc::test
