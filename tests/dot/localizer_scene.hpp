#pragma once
// The dot path's tests through the Localizer: a Scene's camera, mount and map as its setup, the
// scene rendered, a pose compared with the truth.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "algo/pipeline/localizer.hpp"
#include "tests/dot/dot_scene.hpp"

namespace irloc::test {

inline LocalizerSetup setup_for(const Scene& scene, const std::vector<DotMarker>& mapped) {
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = to_rigid(scene.mount);
  setup.dof = Dof::planar3;
  setup.map.dot_markers = mapped;
  return setup;
}

struct Rendered {
  Image8 on, off;
};

inline Rendered render(const Scene& scene) {
  Rendered r;
  scene.render(r.on, r.off);
  return r;
}

inline void expect_pose_near(const PoseEstimate& estimate, const Eigen::Isometry3d& truth, double position_m,
                             double yaw_rad) {
  ASSERT_TRUE(estimate.ok);
  EXPECT_NEAR(estimate.x, truth.translation().x(), position_m);
  EXPECT_NEAR(estimate.y, truth.translation().y(), position_m);
  EXPECT_NEAR(estimate.z, 0.0, 1e-12);
  const double yaw = std::atan2(truth.linear()(1, 0), truth.linear()(0, 0));
  EXPECT_NEAR(wrap_angle(estimate.yaw - yaw), 0.0, yaw_rad);
}

}  // namespace irloc::test
