// Rendered geometry: the intensity centroid of every rendered dot agrees with the camera
// model's projection of the dot's true centre, for a pinhole and a fisheye lens; tape, lamps and
// clutter (strips, crescents) appear where they lie.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "algo/geometry/camera_model.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "host_sim/render/ceiling_layout.hpp"
#include "host_sim/render/marker_view.hpp"
#include "host_sim/render/renderer.hpp"
#include "tests/support/scenario_text.hpp"

namespace irloc::sim {
namespace {

// Largest distance between each dot's centroid in the LED-on minus LED-off radiance image and
// the projection of its centre.
double worst_centroid_error(const Scenario& scenario, int half, int* dots_measured) {
  const CameraModel camera(scenario.camera.intrinsics);
  const Renderer renderer(scenario, camera);
  const int width = renderer.width(), height = renderer.height();
  std::vector<float> on(static_cast<std::size_t>(width * height)), off(on.size());
  renderer.render(0, true, on);
  renderer.render(0, false, off);

  const Trajectory trajectory(scenario.trajectory);
  double worst = 0;
  *dots_measured = 0;
  for (const DotMarker& marker : scenario.map.dot_markers) {
    const std::vector<Eigen::Vector3d> centres = CeilingLayout::dot_centres(marker);
    for (const ProjectedPoint& p : project_points(camera, trajectory.t_w_b(0), scenario.camera.mount, centres)) {
      EXPECT_TRUE(p.visible);
      // Window of (2 half + 1)^2 pixels: the whole dot, none of its neighbours.
      const int cx = static_cast<int>(std::lround(p.pixel.x())), cy = static_cast<int>(std::lround(p.pixel.y()));
      double sum = 0, sx = 0, sy = 0;
      for (int y = cy - half; y <= cy + half; ++y) {
        for (int x = cx - half; x <= cx + half; ++x) {
          if (x < 0 || y < 0 || x >= width || y >= height) continue;
          const std::size_t i = static_cast<std::size_t>(y * width + x);
          const double value = on[i] - off[i];
          sum += value;
          sx += value * x;
          sy += value * y;
        }
      }
      EXPECT_GT(sum, 0);
      worst = std::max(worst, std::hypot(sx / sum - p.pixel.x(), sy / sum - p.pixel.y()));
      ++*dots_measured;
    }
  }
  std::printf("worst dot centroid error: %.4f px over %d dots\n", worst, *dots_measured);
  return worst;
}

// Moves the principal point so that the first marker's centre lands in the middle of the
// (small) image: the lens still sees the marker at the same angle off its axis.
void centre_on_first_marker(Scenario& scenario) {
  CameraIntrinsics& k = scenario.camera.intrinsics;
  k.cx = k.cy = 0;
  const DotMarker& marker = scenario.map.dot_markers.front();
  const Eigen::Vector3d middle =
      marker.origin + 1.5 * marker.pitch * Eigen::Vector3d(std::cos(marker.yaw) + std::sin(marker.yaw),
                                                          std::sin(marker.yaw) - std::cos(marker.yaw), 0);
  const ProjectedPoint p = project_points(CameraModel(k), Trajectory(scenario.trajectory).t_w_b(0),
                                          scenario.camera.mount, {middle}).front();
  k.cx = (k.width - 1) / 2.0 - p.pixel.x();
  k.cy = (k.height - 1) / 2.0 - p.pixel.y();
}

// The renderer's own marker table (ground truth, kept apart from the decoder's on purpose)
// against the spec's test vector, and against the decoder's table for every ID.
TEST(Render, MarkerLayoutAgreesWithTheSpecAndTheDecoder) {
  DotMarker marker;
  marker.id = 1782;
  marker.origin = {1.0, 2.0, 2.6};
  marker.yaw = 0.7;
  const std::vector<Eigen::Vector3d> centres = CeilingLayout::dot_centres(marker);
  // docs/markers.md: ID 1782 has code dots at (0,1) (0,2) (1,0) (1,1) (2,2) (2,3) (3,1) (3,2),
  // plus O, X, Y.
  EXPECT_EQ(centres.size(), 11u);
  for (int id = 0; id < 4096; ++id) {
    marker.id = id;
    const std::vector<Eigen::Vector3d> rendered = CeilingLayout::dot_centres(marker);
    std::vector<Eigen::Vector3d> decoded;
    for (int cell = 0; cell < dot::kCellCount; ++cell) {
      if ((dot::cells_from_id(id) >> cell) & 1u) decoded.push_back(dot::cell_in_world(marker, cell));
    }
    ASSERT_EQ(rendered.size(), decoded.size()) << "ID " << id;
    for (std::size_t k = 0; k < rendered.size(); ++k) ASSERT_LT((rendered[k] - decoded[k]).norm(), 1e-12) << "ID " << id;
  }
}

TEST(Render, DotCentroidsMatchTheProjectionPinhole) {
  // At 1 m with f = 200 px: dots of radius 2.4 px, 8 px apart.
  test::ScenarioText text;
  text.calibration =
      "    image_width: 48\n    image_height: 48\n"
      "    camera_matrix: {rows: 3, cols: 3, data: [200, 0, 79.5, 0, 200, 59.5, 0, 0, 1]}\n"
      "    distortion_model: plumb_bob\n"
      "    distortion_coefficients: {rows: 1, cols: 5, data: [-0.1, 0.02, 0.001, -0.001, 0]}\n";
  text.extra = "render:\n  supersampling: 8\n";
  Scenario scenario = parse_scenario(text.yaml(), "pinhole.yaml");
  centre_on_first_marker(scenario);
  int dots = 0;
  EXPECT_LT(worst_centroid_error(scenario, 4, &dots), 0.05);
  EXPECT_EQ(dots, 11);  // ID 1782: 8 code dots + O, X, Y
}

TEST(Render, DotCentroidsMatchTheProjectionFisheyeOffAxis) {
  test::ScenarioText text;
  text.calibration =
      "    image_width: 40\n    image_height: 40\n"
      "    camera_matrix: {rows: 3, cols: 3, data: [140, 0, 80.2, 0, 140, 59.7, 0, 0, 1]}\n"
      "    distortion_model: equidistant\n"
      "    distortion_coefficients: {rows: 1, cols: 4, data: [0.02, -0.01, 0.003, 0]}\n";
  text.trajectory = "  type: static\n  pose: [0.1, -0.2, 2.0]\n";
  text.map = "  dot_markers:\n    - {id: 4095, origin: [0.35, 0.1, 1.3], yaw: -0.7, radius: 0.012}\n";
  // Dots of radius 1.6 px, 5.2 px apart, 21 degrees off the axis.
  text.extra = "render:\n  supersampling: 8\n";
  Scenario scenario = parse_scenario(text.yaml(), "fisheye.yaml");
  centre_on_first_marker(scenario);
  int dots = 0;
  EXPECT_LT(worst_centroid_error(scenario, 2, &dots), 0.05);
  EXPECT_EQ(dots, 15);
}

TEST(Render, TapeAndLampsAppearWhereTheyAre) {
  test::ScenarioText text;
  text.map = "  square_markers:\n    - name: sq\n      corners: [[-0.3, -0.3, 1.3], [0.3, -0.3, 1.3], [0.3, 0.3, 1.3], [-0.3, 0.3, 1.3]]\n";
  text.calibration =
      "    image_width: 48\n    image_height: 48\n"
      "    camera_matrix: {rows: 3, cols: 3, data: [60, 0, 23.5, 0, 60, 23.5, 0, 0, 1]}\n"
      "    distortion_model: plumb_bob\n"
      "    distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
  text.extra = "render:\n  supersampling: 4\n";
  text.room = "  ceiling_height: 1.3\n  ambient: 0\n  ceiling_reflectance: 0\n  lamps:\n    - {centre: [0, 0], radius: 0.05, radiance: 7}\n";
  const Scenario scenario = parse_scenario(text.yaml(), "tape.yaml");
  const CameraModel camera(scenario.camera.intrinsics);
  const Renderer renderer(scenario, camera);
  std::vector<float> on(static_cast<std::size_t>(renderer.width() * renderer.height())), off(on.size());
  renderer.render(0, true, on);
  renderer.render(0, false, off);
  const auto at = [&](const std::vector<float>& image, const Eigen::Vector3d& world) {
    const ProjectedPoint p = project_points(camera, Trajectory(scenario.trajectory).t_w_b(0), scenario.camera.mount, {world}).front();
    return image[static_cast<std::size_t>(std::lround(p.pixel.y()) * renderer.width() + std::lround(p.pixel.x()))];
  };
  // The lamp shines in both frames, the tape only with the LEDs on, bare ceiling never.
  EXPECT_NEAR(at(off, {0, 0, 1.3}), 7, 1e-4);
  EXPECT_NEAR(at(on, {0, 0, 1.3}), 7, 1e-4);
  EXPECT_GT(at(on, {0, -0.3, 1.3}), 1);       // solid side c0 -> c1
  EXPECT_EQ(at(off, {0, -0.3, 1.3}), 0);
  EXPECT_GT(at(on, {0.3, -0.25, 1.3}), 1);    // dashed side c1 -> c2: 0.05 m from c1 is a dash
  EXPECT_EQ(at(on, {0.3, -0.15, 1.3}), 0);    // 0.15 m: a gap
  EXPECT_EQ(at(on, {0.15, 0.1, 1.3}), 0);     // inside the square
}

// Where the pixel's centre ray meets the ceiling, W x-y.
Eigen::Vector2d ceiling_point(const CameraModel& camera, const Eigen::Isometry3d& t_w_c, double ceiling, int x, int y) {
  Eigen::Vector3d bearing;
  EXPECT_TRUE(camera.unproject(Eigen::Vector2d(x, y), bearing));
  const Eigen::Vector3d d = t_w_c.linear() * bearing;
  const Eigen::Vector3d hit = t_w_c.translation() + (ceiling - t_w_c.translation().z()) / d.z() * d;
  return hit.head<2>();
}

// A strip and a crescent, each against its own geometry written out here: the fraction of every
// pixel covered (the LED-on radiance over that of a ceiling all of retro-reflector, which carries
// the same illumination) is 1 well inside the shape, 0 well outside it and on the crescent's
// shadowed half, sums to the shape's area, and has its centroid at the projection of the shape's.
TEST(Render, ClutterAppearsWhereItLies) {
  test::ScenarioText text;
  text.calibration =
      "    image_width: 64\n    image_height: 64\n"
      "    camera_matrix: {rows: 3, cols: 3, data: [70, 0, 31.5, 0, 70, 31.5, 0, 0, 1]}\n"
      "    distortion_model: plumb_bob\n"
      "    distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
  text.map = "  dot_markers:\n    - {id: 1, origin: [3, 3, 1.3], yaw: 0}\n";  // out of view
  text.room += "  clutter:\n"
               "    - {kind: strip, centre: [0.2, 0.1], length: 0.3, width: 0.08, yaw: 2.0}\n"
               "    - {kind: crescent, centre: [-0.15, -0.12], radius: 0.1, facing: 2.5}\n";
  text.extra = "render:\n  supersampling: 8\n";
  const Scenario scenario = parse_scenario(text.yaml(), "clutter.yaml");
  Scenario all_retro = scenario;  // the reference: retro-reflector wherever the camera looks
  all_retro.room.clutter.clear();
  for (const double y : {-0.8, 0.0, 0.8}) all_retro.room.clutter.push_back({CeilingClutter::Kind::strip, {0, y}, 0, 3.0, 1.0, 0});

  const CameraModel camera(scenario.camera.intrinsics);
  const Renderer renderer(scenario, camera), reference_renderer(all_retro, camera);
  const int width = renderer.width(), height = renderer.height();
  std::vector<float> on(static_cast<std::size_t>(width * height)), off(on.size()), reference(on.size());
  renderer.render(0, true, on);
  renderer.render(0, false, off);
  reference_renderer.render(0, true, reference);

  const Eigen::Isometry3d t_w_b = Trajectory(scenario.trajectory).t_w_b(0);
  const Eigen::Isometry3d t_w_c = t_w_b * scenario.camera.mount;
  const double ceiling = scenario.room.ceiling_height;
  const double distance = ceiling - t_w_c.translation().z();   // 1 m: the image plane is parallel to the ceiling
  const double pixel_area = std::pow(distance / 70, 2);        // ceiling area one pixel sees
  const double margin = 1.5 * distance / 70;                   // a pixel's rays land within this of its centre ray's

  const CeilingClutter& strip = scenario.room.clutter[0];
  const CeilingClutter& crescent = scenario.room.clutter[1];
  const Eigen::Vector2d strip_axis(std::cos(strip.yaw), std::sin(strip.yaw));
  const Eigen::Vector2d facing(std::cos(crescent.yaw), std::sin(crescent.yaw));
  // Signed distances, positive inside: the strip's, the crescent's, from their edges.
  const auto in_strip = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d d = p - strip.centre;
    const double along = d.dot(strip_axis), across = strip_axis.x() * d.y() - strip_axis.y() * d.x();
    return std::min(strip.length / 2 - std::abs(along), strip.width / 2 - std::abs(across));
  };
  const auto in_disc = [&](const Eigen::Vector2d& p) { return crescent.radius - (p - crescent.centre).norm(); };
  const auto in_crescent = [&](const Eigen::Vector2d& p) { return std::min(in_disc(p), (p - crescent.centre).dot(facing)); };

  struct Coverage {
    double sum = 0, sx = 0, sy = 0;
    int inside = 0;
  } strip_coverage, crescent_coverage;
  int outside = 0, shadowed = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * width + x);
      ASSERT_EQ(off[i], 0) << x << ", " << y;  // retro-reflectors shine only with the LEDs on
      ASSERT_GT(reference[i], 0);
      const double covered = on[i] / reference[i];
      const Eigen::Vector2d p = ceiling_point(camera, t_w_c, ceiling, x, y);
      for (auto [distance_inside, coverage] : {std::pair{in_strip(p), &strip_coverage}, std::pair{in_crescent(p), &crescent_coverage}}) {
        if (distance_inside > -margin) {
          coverage->sum += covered;
          coverage->sx += covered * x;
          coverage->sy += covered * y;
        }
        if (distance_inside > margin) {
          EXPECT_NEAR(covered, 1, 1e-6) << x << ", " << y;
          ++coverage->inside;
        }
      }
      if (in_strip(p) < -margin && in_crescent(p) < -margin) {
        EXPECT_EQ(covered, 0) << x << ", " << y;
        ++outside;
        if (in_disc(p) > margin) ++shadowed;
      }
    }
  }
  EXPECT_GT(strip_coverage.inside, 20);
  EXPECT_GT(crescent_coverage.inside, 20);
  EXPECT_GT(shadowed, 20);  // the crescent's dark half was looked at
  EXPECT_GT(outside, 3000);

  // Anti-aliased by area: the coverage sums to the shape's area and centres on its centroid.
  const double half_disc_area = std::numbers::pi * crescent.radius * crescent.radius / 2;
  EXPECT_NEAR(strip_coverage.sum * pixel_area, strip.length * strip.width, 0.01 * strip.length * strip.width);
  EXPECT_NEAR(crescent_coverage.sum * pixel_area, half_disc_area, 0.01 * half_disc_area);
  const Eigen::Vector2d half_disc_centroid = crescent.centre + 4 * crescent.radius / (3 * std::numbers::pi) * facing;
  const std::vector<ProjectedPoint> centroids = project_points(
      camera, t_w_b, scenario.camera.mount, {{strip.centre.x(), strip.centre.y(), ceiling}, {half_disc_centroid.x(), half_disc_centroid.y(), ceiling}});
  const auto centroid = [](const Coverage& c) { return Eigen::Vector2d(c.sx / c.sum, c.sy / c.sum); };
  std::printf("centroid error: strip %.4f px, crescent %.4f px\n", (centroid(strip_coverage) - centroids[0].pixel).norm(),
              (centroid(crescent_coverage) - centroids[1].pixel).norm());
  EXPECT_LT((centroid(strip_coverage) - centroids[0].pixel).norm(), 0.05);
  EXPECT_LT((centroid(crescent_coverage) - centroids[1].pixel).norm(), 0.05);
}

}  // namespace
}  // namespace irloc::sim
