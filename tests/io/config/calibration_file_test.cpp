// Calibration files: ROS camera_info, and the YAML OpenCV's calibration tools write, the latter
// produced by cv::FileStorage itself as the oracle of the format.

#include "io/config/calibration_file.hpp"

#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "io/input_error.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc {
namespace {

using io::load_camera_info;

std::filesystem::path write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// Writes a calibration the way OpenCV's calibration sample does (cv::FileStorage, YAML).
std::filesystem::path write_opencv(const test::TempDir& dir, const cv::Mat& distortion, int fisheye_model = -1,
                                   const std::string& extra_key = "") {
  const std::filesystem::path path = dir / "opencv.yaml";
  cv::FileStorage storage(path.string(), cv::FileStorage::WRITE);
  storage << "calibration_time" << "Sat Nov 21 2026";
  storage << "nr_of_frames" << 25;
  storage << "image_width" << 640 << "image_height" << 480;
  storage << "board_width" << 9 << "board_height" << 6 << "square_size" << 0.025;
  storage << "flags" << 0;
  if (fisheye_model >= 0) storage << "fisheye_model" << fisheye_model;
  storage << "camera_matrix" << (cv::Mat_<double>(3, 3) << 520.5, 0, 319.25, 0, 515.75, 241.5, 0, 0, 1);
  storage << "distortion_coefficients" << distortion;
  storage << "avg_reprojection_error" << 0.21;
  if (!extra_key.empty()) storage << extra_key << 1;
  return path;
}

std::string error_of(const std::filesystem::path& path) {
  try {
    load_camera_info(path);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(CalibrationFile, ReadsRosCameraInfo) {
  test::TempDir dir;
  const CameraIntrinsics k = load_camera_info(write(dir, "ros.yaml", R"(image_width: 640
image_height: 480
camera_name: up
camera_matrix: {rows: 3, cols: 3, data: [500, 0, 320.5, 0, 501, 240.5, 0, 0, 1]}
distortion_model: plumb_bob
distortion_coefficients: {rows: 1, cols: 5, data: [-0.1, 0.01, 0.001, -0.002, 0.0005]}
)"));
  EXPECT_EQ(k.width, 640);
  EXPECT_EQ(k.model, LensModel::plumb_bob);
  EXPECT_DOUBLE_EQ(k.fy, 501);
  EXPECT_DOUBLE_EQ(k.distortion[4], 0.0005);
}

TEST(CalibrationFile, ReadsOpenCvPinholeCalibration) {
  test::TempDir dir;
  const CameraIntrinsics k =
      load_camera_info(write_opencv(dir, (cv::Mat_<double>(5, 1) << -0.28, 0.09, 1e-3, -5e-4, -0.01)));
  EXPECT_EQ(k.width, 640);
  EXPECT_EQ(k.height, 480);
  EXPECT_EQ(k.model, LensModel::plumb_bob);
  EXPECT_DOUBLE_EQ(k.fx, 520.5);
  EXPECT_DOUBLE_EQ(k.fy, 515.75);
  EXPECT_DOUBLE_EQ(k.cx, 319.25);
  EXPECT_DOUBLE_EQ(k.cy, 241.5);
  EXPECT_DOUBLE_EQ(k.distortion[0], -0.28);
  EXPECT_DOUBLE_EQ(k.distortion[3], -5e-4);
  EXPECT_DOUBLE_EQ(k.distortion[4], -0.01);
}

TEST(CalibrationFile, ReadsOpenCvFisheyeCalibration) {
  test::TempDir dir;
  const CameraIntrinsics k =
      load_camera_info(write_opencv(dir, (cv::Mat_<double>(4, 1) << -0.01, 0.005, -0.002, 0.0003), 1));
  EXPECT_EQ(k.model, LensModel::equidistant);
  EXPECT_DOUBLE_EQ(k.distortion[3], 0.0003);
}

TEST(CalibrationFile, RejectsWhatTheModelsCannotRepresent) {
  test::TempDir dir;
  // The rational model's 8 coefficients.
  EXPECT_NE(error_of(write_opencv(dir, cv::Mat::zeros(8, 1, CV_64F))).find("distortion_coefficients"), std::string::npos);
  // A fisheye file with 5 coefficients.
  EXPECT_NE(error_of(write_opencv(dir, cv::Mat::zeros(5, 1, CV_64F), 1)).find("distortion_coefficients"), std::string::npos);
  // An integer matrix.
  EXPECT_NE(error_of(write_opencv(dir, cv::Mat::zeros(5, 1, CV_32S))).find("dt"), std::string::npos);
  // A key neither format has.
  EXPECT_NE(error_of(write_opencv(dir, cv::Mat::zeros(5, 1, CV_64F), -1, "focal_lenght")).find("focal_lenght"),
            std::string::npos);
  EXPECT_NE(error_of(write_opencv(dir, cv::Mat::zeros(5, 1, CV_64F), 2)).find("fisheye_model"), std::string::npos);
}

}  // namespace
}  // namespace irloc
