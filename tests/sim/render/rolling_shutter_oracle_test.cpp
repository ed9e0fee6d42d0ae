// A rolling shutter rendered exactly: under fast motion, the intensity centroid of every rendered
// dot lies where OpenCV's projectPoints puts the dot's centre from the camera pose at the time
// of the row it lands in (row v exposed at t + v * line_time, conventions.md), found row by row;
// and, so that the check can fail, far from where the pose at t (a global shutter) puts it.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/render/ceiling_layout.hpp"
#include "host_sim/render/renderer.hpp"
#include "tests/support/opencv_projection.hpp"
#include "tests/support/scenario_text.hpp"

namespace irloc::sim {
namespace {

constexpr double kLineTime = 200e-6;  // s: the 128 rows are exposed over 25.6 ms

struct Offsets {
  double worst_to_rolling = 0;  // px, centroid to the rolling-shutter projection
  double worst_to_global = 0;   // px, centroid to the projection from the pose at t
  int dots = 0;
};

// The marker's middle is at the world origin; the camera is over it at t.
Offsets measure(const std::string& trajectory, const std::string& mount) {
  test::ScenarioText text;
  text.calibration =
      "    image_width: 96\n    image_height: 128\n"
      "    camera_matrix: {rows: 3, cols: 3, data: [220, 0, 47.5, 0, 220, 63.5, 0, 0, 1]}\n"
      "    distortion_model: plumb_bob\n"
      "    distortion_coefficients: {rows: 1, cols: 5, data: [-0.1, 0.02, 0.001, -0.001, 0]}\n";
  text.camera_timing = "  frame_rate: 30\n  exposure: 0.0001\n  line_time_ns: 200000\n";
  text.trajectory = trajectory;
  text.mount = mount;
  text.map = "  dot_markers:\n    - {id: 1782, origin: [-0.0786, 0.0319, 1.3], yaw: 0.4, radius: 0.012}\n";
  text.extra = "render:\n  supersampling: 6\n";
  const Scenario scenario = parse_scenario(text.yaml(), "rolling.yaml");
  const CameraIntrinsics& k = scenario.camera.intrinsics;
  const CameraModel camera(k);
  const Renderer renderer(scenario, camera);
  std::vector<float> on(static_cast<std::size_t>(k.width * k.height)), off(on.size());
  const double t = 0.1;
  renderer.render(t, true, on);
  renderer.render(t, false, off);

  Offsets offsets;
  for (const Eigen::Vector3d& centre : CeilingLayout::dot_centres(scenario.map.dot_markers.front())) {
    const Eigen::Vector2d expected =
        test::opencv_rolling_projection(centre, k, kLineTime, [&](double after) { return renderer.t_w_c(t + after); });
    const Eigen::Vector2d global = test::opencv_projection(centre, renderer.t_w_c(t), k);
    if (!expected.allFinite()) {
      ADD_FAILURE() << "the dot lands in no row";
      continue;
    }
    constexpr int kHalf = 3;  // the whole dot (radius 2.6 px), none of its neighbours (8.8 px apart)
    const int cx = static_cast<int>(std::lround(expected.x())), cy = static_cast<int>(std::lround(expected.y()));
    double sum = 0, sx = 0, sy = 0;
    for (int y = cy - kHalf; y <= cy + kHalf; ++y) {
      for (int x = cx - kHalf; x <= cx + kHalf; ++x) {
        if (x < 0 || y < 0 || x >= k.width || y >= k.height) continue;
        const std::size_t i = static_cast<std::size_t>(y * k.width + x);
        const double value = on[i] - off[i];
        sum += value;
        sx += value * x;
        sy += value * y;
      }
    }
    EXPECT_GT(sum, 0);
    const Eigen::Vector2d centroid(sx / sum, sy / sum);
    offsets.worst_to_rolling = std::max(offsets.worst_to_rolling, (centroid - expected).norm());
    offsets.worst_to_global = std::max(offsets.worst_to_global, (centroid - global).norm());
    ++offsets.dots;
  }
  std::printf("%d dots: worst %.4f px from the rolling-shutter projection, %.2f px from the global one\n", offsets.dots,
              offsets.worst_to_rolling, offsets.worst_to_global);
  return offsets;
}

TEST(RollingShutterRender, DotsDrivingAtOneMetrePerSecondLandWhereTheirRowsPoseProjectsThem) {
  // At t = 0.1 s the robot is at the origin heading +x.
  const Offsets offsets = measure("  type: waypoints\n  points: [[-0.1, 0], [0.9, 0]]\n  speed: 1.0\n",
                                  "{preset: up, xyz: [0, 0, 0.3]}");
  EXPECT_EQ(offsets.dots, 11);
  EXPECT_LT(offsets.worst_to_rolling, 0.05);
  EXPECT_GT(offsets.worst_to_global, 2.0);
}

TEST(RollingShutterRender, DotsSpinningFastLandWhereTheirRowsPoseProjectsThem) {
  // The camera 0.1 m ahead of a robot turning on the spot at 6 rad/s: over the marker at t = 0.1 s.
  const Offsets offsets = measure("  type: spin\n  centre: [-0.0825, -0.0565]\n  yaw: 0.0\n  rate: 6.0\n",
                                  "{preset: up, xyz: [0.1, 0, 0.3]}");
  EXPECT_EQ(offsets.dots, 11);
  EXPECT_LT(offsets.worst_to_rolling, 0.05);
  EXPECT_GT(offsets.worst_to_global, 1.0);
}

}  // namespace
}  // namespace irloc::sim
