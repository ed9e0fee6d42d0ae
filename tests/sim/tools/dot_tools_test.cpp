// The dot path end to end on a written dataset: irlocd replay writes `dot` poses, and the
// irloc-sim tools calibrate the mount from a spin in place and fit the grey-level model.

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "io/config/config_file.hpp"
#include "io/input_error.hpp"
#include "io/dataset/dataset_writer.hpp"
#include "host_sim/tools/dot_tools.hpp"
#include "tests/dot/dot_scene.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

constexpr int kPairs = 24;
const Eigen::Vector2d kSpinCentre(0.2, 0.1);
const Eigen::Vector3d kMountXyz(0.12, -0.05, 0.3);

// A robot spinning in place under three markers, written as a strobed dataset with its config.
class SpinDataset : public ::testing::Test {
 protected:
  // Rendered once for the suite.
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    test::Scene scene;
    scene.camera = test::pinhole_camera(480, 360, 380);
    scene.mount = test::up_mount(kMountXyz);
    const std::vector<DotMarker> markers = {test::ceiling_marker(1782, 0.3, 0.4, 0.0),
                                            test::ceiling_marker(421, -0.2, -0.25, 1.2),
                                            test::ceiling_marker(3003, 0.5, -0.3, -2.0)};
    for (const DotMarker& marker : markers) scene.add_marker(marker);
    io::DatasetWriter writer(*dir_ / "dataset");
    for (int k = 0; k < kPairs; ++k) {
      scene.world_from_base = test::level_pose(kSpinCentre.x(), kSpinCentre.y(), 2 * std::numbers::pi * k / kPairs);
      scene.seed = static_cast<unsigned>(k + 1);
      Image8 on, off;
      scene.render(on, off);
      const auto seq = static_cast<std::uint64_t>(2 * k);
      writer.write(Frame{seq, static_cast<std::int64_t>(seq) * 33'000'000, false, ImageView8(off.view())});
      writer.write(Frame{seq + 1, static_cast<std::int64_t>(seq + 1) * 33'000'000, true, ImageView8(on.view())});
    }
    std::ofstream(*dir_ / "calib.yaml") << "image_width: 480\nimage_height: 360\n"
                                          "camera_matrix: {rows: 3, cols: 3, data: [380, 0, 239.5, 0, 380, 179.5, 0, 0, 1]}\n"
                                          "distortion_model: plumb_bob\n"
                                          "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
    std::ofstream map(*dir_ / "map.yaml");
    map << "dot_markers:\n";
    for (const DotMarker& m : markers) {
      map << "  - {id: " << m.id << ", origin: [" << m.origin.x() << ", " << m.origin.y() << ", " << m.origin.z()
          << "], yaw: " << m.yaw << "}\n";
    }
    map.close();
    std::ofstream(config()) << "camera:\n  calibration: calib.yaml\n"
                               "  mount: {preset: up, xyz: [0.12, -0.05, 0.3]}  # the truth\n"
                               "robot:\n  dof: 3\nmap: map.yaml\n";
  }

  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }

  static std::filesystem::path config() { return *dir_ / "config.yaml"; }
  static std::filesystem::path dataset() { return *dir_ / "dataset"; }

  static test::TempDir* dir_;
};

test::TempDir* SpinDataset::dir_ = nullptr;

using test::read_text;

TEST_F(SpinDataset, IrlocdReplayWritesDotPoses) {
  const std::filesystem::path csv = *dir_ / "pose.csv";
  const test::ProcessResult run = test::run_to_end({IRLOCD_PATH, "--config", config().string(), "--camera",
                                                   "dir:" + dataset().string(), "--serial", "none", "--pose-csv", csv.string()},
                                                  *dir_ / "stderr.txt");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  std::istringstream rows(read_text(csv));
  std::string row;
  std::getline(rows, row);  // header
  int ok = 0;
  while (std::getline(rows, row)) {
    EXPECT_NE(row.find(",dot"), std::string::npos) << row;
    if (row.find(",ok,") == std::string::npos) continue;
    ++ok;
    // seq,t_ns,status,x,y,... : the base stays on the spin centre.
    std::istringstream fields(row);
    std::string seq, t, state, x, y;
    std::getline(fields, seq, ',');
    std::getline(fields, t, ',');
    std::getline(fields, state, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    EXPECT_NEAR(std::stod(x), kSpinCentre.x(), 0.003) << row;
    EXPECT_NEAR(std::stod(y), kSpinCentre.y(), 0.003) << row;
  }
  EXPECT_EQ(ok, kPairs);
}

TEST_F(SpinDataset, CalibrateMountFindsTheOffsetAndWritesIt) {
  const sim::MountCalibration mount = sim::calibrate_mount(config(), dataset());
  EXPECT_EQ(mount.poses, static_cast<std::size_t>(kPairs));
  EXPECT_NEAR(mount.fit.offset.x(), kMountXyz.x(), 0.003);
  EXPECT_NEAR(mount.fit.offset.y(), kMountXyz.y(), 0.003);
  EXPECT_NEAR(mount.fit.centre.x(), kSpinCentre.x(), 0.003);
  EXPECT_NEAR(mount.fit.centre.y(), kSpinCentre.y(), 0.003);
  const std::filesystem::path written = *dir_ / "calibrated.yaml";
  sim::write_mount(config(), written, mount);
  const io::RobotConfig reread = io::load_robot_config(written);
  EXPECT_NEAR(reread.setup.mount.translation.x(), kMountXyz.x(), 0.003);
  EXPECT_NEAR(reread.setup.mount.translation.y(), kMountXyz.y(), 0.003);
  EXPECT_DOUBLE_EQ(reread.setup.mount.translation.z(), kMountXyz.z());
}

TEST_F(SpinDataset, FitConfidenceFindsTheDotLevel) {
  const sim::ConfidenceFit fit = sim::fit_confidence(config(), dataset());
  EXPECT_GT(fit.samples, static_cast<std::size_t>(kPairs * 20));
  // The rendered dots peak 150 grey levels above the background; their blob means lie below that.
  EXPECT_GT(fit.model.dot.mean, 60.0);
  EXPECT_LT(fit.model.dot.mean, 150.0);
  EXPECT_GE(fit.model.dot.mean, fit.model.clutter.mean);
  EXPECT_NE(sim::grey_levels_yaml(fit.model).find("grey_levels:"), std::string::npos);
}

TEST_F(SpinDataset, CalibrateMountNeedsTurning) {
  // The first three pairs turn 30 deg: too little for a circle.
  test::TempDir short_spin;
  std::ofstream index(short_spin / "frames.csv");
  index << "seq,t_ns,led,file\n";
  for (int seq = 0; seq < 6; ++seq) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.pgm", seq);
    std::filesystem::copy_file(dataset() / name, short_spin / name);
    index << seq << "," << seq * 33'000'000 << "," << seq % 2 << "," << name << "\n";
  }
  index.close();
  EXPECT_THROW(sim::calibrate_mount(config(), short_spin.path()), io::InputError);
}

}  // namespace
}  // namespace irloc
