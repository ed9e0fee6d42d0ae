// The cairo plots draw what they are given: estimate dots appear exactly when there are ok poses.

#include <gtest/gtest.h>

#include <cairo.h>

#include "host_sim/plots/plots.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::sim {
namespace {

// Pixels of the PNG in one colour (8-bit channels), to within rounding.
int coloured_pixels(const std::filesystem::path& png, int red, int green, int blue) {
  cairo_surface_t* surface = cairo_image_surface_create_from_png(png.c_str());
  EXPECT_EQ(cairo_surface_status(surface), CAIRO_STATUS_SUCCESS);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  int count = 0;
  for (int y = 0; y < cairo_image_surface_get_height(surface); ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + y * stride);
    for (int x = 0; x < cairo_image_surface_get_width(surface); ++x) {
      const int r = (row[x] >> 16) & 0xff, g = (row[x] >> 8) & 0xff, b = row[x] & 0xff;
      count += std::abs(r - red) <= 2 && std::abs(g - green) <= 2 && std::abs(b - blue) <= 2;
    }
  }
  cairo_surface_destroy(surface);
  return count;
}

// The estimate colour (0.85, 0.20, 0.10).
int estimate_coloured_pixels(const std::filesystem::path& png) { return coloured_pixels(png, 217, 51, 26); }

TEST(Plots, EstimatesAreDrawnOnlyWhenThereAreOkPoses) {
  const test::TempDir dir;
  std::vector<TruthRow> truth;
  std::vector<PoseEstimate> none, some;
  for (int i = 0; i < 20; ++i) {
    TruthRow row;
    row.seq = static_cast<std::uint64_t>(i);
    row.t_ns = 1'000'000'000 + i * 50'000'000;
    row.x = 0.1 * i;
    truth.push_back(row);
    PoseEstimate pose;
    pose.seq = row.seq;
    pose.t_ns = row.t_ns;
    none.push_back(pose);
    pose.ok = true;
    pose.x = row.x + 0.02;
    some.push_back(pose);
  }
  MarkerMap map;
  map.dot_markers.push_back({7, Eigen::Vector3d(1, 0.5, 2.5), 0.3, 0.04, 0.01});
  const MetricsSpec thresholds;
  const Metrics without = compute_metrics(truth, none, {}, thresholds);
  const Metrics with = compute_metrics(truth, some, {}, thresholds);

  plot_trajectory(dir / "none.png", truth, none, without, map);
  plot_trajectory(dir / "some.png", truth, some, with, map);
  plot_errors(dir / "errors_none.png", truth, none, without);
  plot_errors(dir / "errors_some.png", truth, some, with);
  // Legends carry one swatch of the estimate colour (14 x 10 pixels); dots add more.
  EXPECT_EQ(estimate_coloured_pixels(dir / "none.png"), 140);
  EXPECT_GT(estimate_coloured_pixels(dir / "some.png"), 140 + 20 * 10);
  EXPECT_EQ(estimate_coloured_pixels(dir / "errors_none.png"), 140);
  EXPECT_GT(estimate_coloured_pixels(dir / "errors_some.png"), 140 + 20 * 4);  // small dots, some on the axis
}

// The survey picture: truth crosses (green) only when a truth is given; a red move line only for
// a marker that moved more than the threshold (the legend's swatch aside).
TEST(Plots, SurveyMapDrawsTheTruthWhenGivenAndTheMoves) {
  test::TempDir dir;
  MarkerMap before;
  before.dot_markers = {DotMarker{1000, {0, 0, 2.6}, 0, 0.04, 0.01, true, std::nullopt},
                        DotMarker{1037, {1.8, 0, 2.6}, 0, 0.04, 0.01, false, std::nullopt}};
  MarkerMap after = before;
  after.dot_markers[1].sigma = Eigen::Vector4d(0.001, 0.001, 0.001, 0.001);
  plot_survey_map(dir / "with_truth.png", before, after, &before);
  plot_survey_map(dir / "still.png", before, after, nullptr);
  after.dot_markers[1].origin.y() += 0.8;
  plot_survey_map(dir / "moved.png", before, after, nullptr);
  const auto green = [](const std::filesystem::path& png) { return coloured_pixels(png, 26, 153, 51); };
  const auto red = [](const std::filesystem::path& png) { return coloured_pixels(png, 217, 26, 26); };
  EXPECT_GT(green(dir / "with_truth.png"), green(dir / "still.png") + 20);
  EXPECT_EQ(green(dir / "still.png"), 0);
  EXPECT_GT(red(dir / "moved.png"), red(dir / "still.png") + 50);
}

}  // namespace
}  // namespace irloc::sim
