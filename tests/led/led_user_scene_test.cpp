// The user scene (host_sim/scenarios/led_wall_user.yaml) in small: a few of its strided
// strobe pairs ray-traced by the Renderer at one ray per pixel, through the LED source. The
// scenario's own run (irloc-sim run) is the measured figure (docs/led_landmarks.md); this checks
// that the scene renders what it says and that the source poses it.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "algo/core/image.hpp"
#include "algo/markers/led/led_landmark_source.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/render/noise.hpp"
#include "host_sim/render/renderer.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {
namespace {

TEST(LedUserScene, KeepsEverySixthPairAndPosesTheStridedPairsWithinTheGoal) {
  Scenario scenario = load_scenario(IRLOC_SOURCE_DIR "/host_sim/scenarios/led_wall_user.yaml");
  scenario.supersampling = 1;
  ASSERT_EQ(scenario.pair_stride, 6);
  EXPECT_FALSE(is_dropped(scenario, 12));  // pair 6
  EXPECT_FALSE(is_dropped(scenario, 13));
  EXPECT_TRUE(is_dropped(scenario, 2));
  EXPECT_TRUE(is_dropped(scenario, 11));

  const CameraModel camera(scenario.camera.intrinsics);
  const Renderer renderer(scenario, camera);
  const Sensor sensor(scenario.camera, scenario.seed);
  const int width = renderer.width(), height = renderer.height();
  const RigidTransform mount = to_rigid(scenario.camera.mount);
  const SourceSetup setup{scenario.camera.intrinsics, mount, scenario.dof, scenario.map, scenario.camera.bit_depth};
  led::LedLandmarkSource source(setup, led::LedSourceConfig{});

  std::vector<float> radiance(static_cast<std::size_t>(width * height));
  Image8 on_image(width, height), off_image(width, height);
  // Three strided pairs at the start (0.2 s apart: tracked), two at the end of the drive.
  for (const std::uint64_t pair_index : {0u, 6u, 12u, 168u, 174u}) {
    Frame frames[2];
    for (const bool led_on : {true, false}) {
      const std::uint64_t seq = 2 * pair_index + (led_on ? 0 : 1);
      const double t = static_cast<double>(seq) / scenario.camera.frame_rate;
      renderer.render(t, led_on, radiance);
      Image8& image = led_on ? on_image : off_image;
      for (int y = 0; y < height; ++y) {
        sensor.expose_row(std::span<const float>(radiance.data() + static_cast<std::size_t>(y * width),
                                                 static_cast<std::size_t>(width)),
                          seq, y, image.view().row(y));
      }
      frames[led_on ? 0 : 1] = Frame{seq, frame_time_ns(scenario, seq), led_on, ImageView8(image.view())};
    }
    SourceResult result;
    source.process(SourceInput{frames[0], &frames[1]}, result);
    ASSERT_TRUE(result.ok) << "pair " << pair_index << ": " << result.outcome;
    const double t = static_cast<double>(2 * pair_index) / scenario.camera.frame_rate;
    const RigidTransform truth = to_rigid(renderer.trajectory().t_w_b(t));
    EXPECT_LT((result.world_from_base.translation - truth.translation).norm(), 0.015) << "pair " << pair_index;
    const double yaw_error = wrap_angle(rpy_from_rotation(result.world_from_base.rotation).yaw -
                                        rpy_from_rotation(truth.rotation).yaw);
    EXPECT_LT(std::abs(yaw_error), 0.2 * std::numbers::pi / 180) << "pair " << pair_index;
    // Every LED the pose names is the one at that pixel.
    const RigidTransform camera_from_world = (truth * mount).inverse();
    EXPECT_GE(result.observations.size(), 3u);
    for (const PointObservation& observation : result.observations) {
      Eigen::Vector2d pixel;
      ASSERT_TRUE(camera.project(camera_from_world * observation.world, pixel));
      EXPECT_LT((pixel - observation.pixel).norm(), 1.0) << "pair " << pair_index;
    }
  }
}

}  // namespace
}  // namespace irloc::sim
