// irlocd --calibrate's end of the drive (firmware/calibration_run): from the dot source's
// results of a synthetic drive to the files, read back by the config and calibration loaders.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "algo/pipeline/localizer.hpp"
#include "firmware/calibration_run.hpp"
#include "io/config/calibration_file.hpp"
#include "io/config/camera_info_writer.hpp"
#include "io/config/config_file.hpp"
#include "tests/calibration/synthetic_drive.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc::test {
namespace {

CameraIntrinsics believed_camera() {
  CameraIntrinsics k = true_camera();
  k.fx *= 1.005;
  k.fy *= 1.005;
  k.cx += 2;
  k.distortion[0] *= 1.05;
  return k;
}

// The true mount rotated 0.2 deg about the base's x and moved 3 mm forward: what the config says.
constexpr double kBelievedRoll = 0.2 * std::numbers::pi / 180;
RigidTransform believed_mount() {
  RigidTransform mount = true_mount();
  mount.rotation = rotation_from_rpy(kBelievedRoll, 0, 0) * mount.rotation;
  mount.translation.x() += 0.003;
  return mount;
}

class CalibrationRunTest : public ::testing::Test {
 protected:
  // config.yaml (with a dot: section that must survive), calib.yaml and map.yaml in dir_/input.
  void write_input(const MarkerMap& map) {
    const std::filesystem::path input = dir_ / "input";
    std::filesystem::create_directories(input);
    std::ofstream(input / "calib.yaml") << io::camera_info_yaml(believed_camera(), "test", "");
    std::ofstream out(input / "map.yaml");
    out << (map.dot_markers.empty() ? "led_landmarks:\n  - {name: L1, position: [0, 0, 2.6]}\n" : "dot_markers:\n");
    for (const DotMarker& marker : map.dot_markers) {
      out << "  - {id: " << marker.id << ", origin: [" << io::yaml_number(marker.origin.x()) << ", "
          << io::yaml_number(marker.origin.y()) << ", " << io::yaml_number(marker.origin.z())
          << "], yaw: " << io::yaml_number(marker.yaw) << "}\n";
    }
    out.close();
    std::ofstream(config_file()) << "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0.103, 0.02, 0.3], rpy: ["
                                 << io::yaml_number(kBelievedRoll) << ", 0, 0]}\nrobot:\n  dof: 3\nmap: map.yaml\n"
                                 << "dot:\n  marker_gate_px: 2.5\n";
  }
  std::filesystem::path config_file() const { return dir_ / "input" / "config.yaml"; }
  std::filesystem::path out_dir() const { return dir_ / "out" / "calibrated"; }

  // Feeds `run` the dot results of a synthetic drive seen through the true calibration; returns
  // how many poses with dots it had.
  static std::size_t feed(firmware::CalibrationRun& run, const std::vector<TimedPose>& path) {
    const SyntheticDrive drive = observe_drive(path, marker_grid(), true_camera(), true_mount(), believed_camera(),
                                               believed_mount(), 0.1, 5);
    for (const calibration::DriveFrame& frame : drive.observations.frames()) {
      SourceResult result;
      result.clear(SourceKind::dot);
      result.ok = true;
      result.world_from_base = frame.world_from_base;
      for (std::size_t i = frame.first; i < frame.first + frame.count; ++i) {
        result.observations.push_back(drive.observations.observations()[i]);
      }
      // Every other pose only above the confidence floor: both count.
      result.ok = (frame.t_ns / 1'000'000) % 2 == 0;
      run.add(frame.t_ns, result);
      result.kind = SourceKind::square;  // other sources' results are not dot observations
      run.add(frame.t_ns + 1, result);
      result.kind = SourceKind::dot;  // a plain fit of a rolling shutter's rows: its pixels not at t_ns
      result.pose_delay_ns = 11'000'000;
      run.add(frame.t_ns + 3, result);
      result.pose_delay_ns = 0;  // a dot attempt whose fit did not run has no observations
      result.observations.clear();
      run.add(frame.t_ns + 2, result);
    }
    return drive.observations.frames().size();
  }

  TempDir dir_;
};

TEST_F(CalibrationRunTest, WritesARefinedConfigThatLoadsBack) {
  write_input(marker_grid());
  const io::RobotConfig input = io::load_robot_config(config_file());
  const Localizer localizer(input.setup);
  firmware::CalibrationRun run(out_dir(), config_file(), input.map_file, localizer);
  const std::vector<TimedPose> path = wheeled_drive();
  const std::size_t fed = feed(run, path);
  EXPECT_EQ(run.drive().frames().size(), fed);
  EXPECT_GT(run.drive().frames().size(), 200u);
  const std::string summary = run.finish();
  EXPECT_NE(summary.find(out_dir().string()), std::string::npos) << summary;

  const io::RobotConfig refined = io::load_robot_config(out_dir() / "config.yaml");
  EXPECT_EQ(refined.calibration_file, out_dir() / "calib.yaml");
  EXPECT_EQ(refined.map_file, std::filesystem::absolute(input.map_file).lexically_normal());
  EXPECT_TRUE(refined.map_file.is_absolute());
  EXPECT_EQ(refined.setup.map.dot_markers.size(), marker_grid().dot_markers.size());
  EXPECT_EQ(refined.setup.dot.marker_gate_px, 2.5);  // the rest of the config is kept
  // Mount and lens closer to the truth than the input by far.
  const Eigen::AngleAxisd rotation_error(refined.setup.mount.rotation.transpose() * true_mount().rotation);
  EXPECT_LT(rotation_error.angle(), 0.02 * std::numbers::pi / 180);
  EXPECT_NEAR(refined.setup.mount.translation.x(), true_mount().translation.x(), 0.0015);
  EXPECT_NEAR(refined.setup.camera.fx, true_camera().fx, 1.5);
  EXPECT_NEAR(refined.setup.camera.cx, true_camera().cx, 0.5);
  EXPECT_NEAR(refined.setup.camera.distortion[0], true_camera().distortion[0], 0.002);
  EXPECT_EQ(refined.setup.camera.model, LensModel::plumb_bob);

  const std::string report = read_text(out_dir() / "calibration_report.txt");
  for (const char* expected : {"before", "after", "fx", "mount yaw", "sigma", "mount y      prior",
                               "no motion of a wheeled base shows where on its axle"}) {
    EXPECT_NE(report.find(expected), std::string::npos) << expected << "\n" << report;
  }
  const std::string residuals = read_text(out_dir() / "residuals.csv");
  EXPECT_EQ(std::count(residuals.begin(), residuals.end(), '\n'),
            static_cast<std::ptrdiff_t>(run.drive().observations().size() + 1));
  std::vector<std::string> written;  // and no temporary file
  for (const auto& entry : std::filesystem::directory_iterator(out_dir())) written.push_back(entry.path().filename().string());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{"calib.yaml", "calibration_report.txt", "config.yaml", "residuals.csv"}));
}

TEST_F(CalibrationRunTest, TooShortADriveIsAnErrorNamingTheOption) {
  write_input(marker_grid());
  const io::RobotConfig input = io::load_robot_config(config_file());
  const Localizer localizer(input.setup);
  firmware::CalibrationRun run(out_dir(), config_file(), input.map_file, localizer);
  const std::vector<TimedPose> path = wheeled_drive();
  feed(run, std::vector<TimedPose>(path.begin(), path.begin() + 6));
  const std::string message = input_error_message([&] { run.finish(); });
  EXPECT_NE(message.find("--calibrate: no calibration from this drive"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(out_dir() / "config.yaml"));
}

TEST_F(CalibrationRunTest, AMapWithoutDotMarkersIsRefusedAtStart) {
  write_input(MarkerMap{});
  const io::RobotConfig input = io::load_robot_config(config_file());
  const Localizer localizer(input.setup);
  const std::string message =
      input_error_message([&] { firmware::CalibrationRun run(out_dir(), config_file(), input.map_file, localizer); });
  EXPECT_NE(message.find("has no dot markers"), std::string::npos) << message;
  EXPECT_NE(message.find("map.yaml"), std::string::npos) << message;
}

}  // namespace
}  // namespace irloc::test
