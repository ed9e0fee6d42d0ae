// irlocd --calibrate's residuals.csv read back, and its picture: arrows where the residuals are.

#include <gtest/gtest.h>

#include <cairo.h>

#include <fstream>

#include "host_sim/plots/calibration_residuals.hpp"
#include "host_sim/plots/plots.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::sim {
namespace {

TEST(CalibrationResiduals, ReadsRowsAndNamesTheBadLine) {
  const test::TempDir dir;
  std::ofstream(dir / "residuals.csv") << "u,v,before_du,before_dv,after_du,after_dv\n"
                                       << "10.5,20,1.5,-2,0.01,0.02\n"
                                       << "11,21,1,2,x,0\n";
  const std::string message = test::input_error_message([&] { read_calibration_residuals(dir / "residuals.csv"); });
  EXPECT_NE(message.find("residuals.csv:3: expected six numbers"), std::string::npos) << message;
  std::ofstream(dir / "good.csv") << "u,v,before_du,before_dv,after_du,after_dv\n10.5,20,1.5,-2,0.01,0.02\n";
  const std::vector<DotResidualRow> rows = read_calibration_residuals(dir / "good.csv");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].pixel, Eigen::Vector2d(10.5, 20));
  EXPECT_EQ(rows[0].before, Eigen::Vector2d(1.5, -2));
  EXPECT_EQ(rows[0].after, Eigen::Vector2d(0.01, 0.02));
}

// Large residuals before, none after: the before panel (left half) has arrows in the estimate
// colour, the after panel none.
TEST(CalibrationResiduals, PictureShowsArrowsWhereTheResidualsAre) {
  const test::TempDir dir;
  std::vector<DotResidualRow> rows;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d pixel(10 + 3.1 * i, 20 + 2.2 * i);
    rows.push_back({pixel, (pixel - Eigen::Vector2d(320, 240)) * 0.01, Eigen::Vector2d::Zero()});
  }
  plot_calibration_residuals(dir / "residuals.png", rows, 640, 480);
  cairo_surface_t* surface = cairo_image_surface_create_from_png((dir / "residuals.png").c_str());
  ASSERT_EQ(cairo_surface_status(surface), CAIRO_STATUS_SUCCESS);
  const int width = cairo_image_surface_get_width(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  int left = 0, right = 0;
  for (int y = 0; y < cairo_image_surface_get_height(surface); ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + y * cairo_image_surface_get_stride(surface));
    for (int x = 0; x < width; ++x) {
      const int r = (row[x] >> 16) & 0xff, g = (row[x] >> 8) & 0xff, b = row[x] & 0xff;
      const bool arrow = r > 150 && g < 120 && b < 100;
      (x < width / 2 ? left : right) += arrow;
    }
  }
  cairo_surface_destroy(surface);
  EXPECT_GT(left, 200);
  EXPECT_EQ(right, 0);
}

}  // namespace
}  // namespace irloc::sim
