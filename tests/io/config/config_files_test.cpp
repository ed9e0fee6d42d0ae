#include <fstream>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/calibration_file.hpp"
#include "io/config/config_file.hpp"
#include "io/config/map_file.hpp"
#include "io/input_error.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr const char* kCalibration = R"(image_width: 640
image_height: 480
camera_name: ceiling
camera_matrix:
  rows: 3
  cols: 3
  data: [500, 0, 319.5, 0, 501, 239.5, 0, 0, 1]
distortion_model: plumb_bob
distortion_coefficients:
  rows: 1
  cols: 5
  data: [-0.1, 0.01, 0.001, -0.002, 0.0005]
rectification_matrix:
  rows: 3
  cols: 3
  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]
)";

constexpr const char* kMap = R"(dot_markers:
  - id: 1782
    origin: [1.0, 2.0, 2.6]
    yaw: 0.5
  - id: 7
    origin: [3.0, 2.0, 2.6]
    yaw: 0.0
    pitch: 0.05
    radius: 0.012
square_markers:
  - name: hall
    corners: [[0, 0, 2.5], [2, 0, 2.5], [2, 2, 2.5], [0, 2, 2.5]]
led_landmarks:
  - name: L1
    position: [0, 5, 1.5]
    direction: [0, -2, 0]
    half_angle: 0.5
)";

constexpr const char* kConfig = R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0.1, 0, 0.3], rpy: [0, 0, 0]}
robot:
  dof: 3
map: map.yaml
)";

class ConfigFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    write("calib.yaml", kCalibration);
    write("map.yaml", kMap);
    write("config.yaml", kConfig);
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  // The message of the InputError that loading the config throws.
  std::string config_error() {
    return test::input_error_message([&] { load_robot_config(dir_ / "config.yaml"); });
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  test::TempDir dir_;
};

TEST_F(ConfigFiles, LoadsTheSpecExample) {
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.dof, Dof::planar3);
  EXPECT_EQ(config.setup.camera.width, 640);
  EXPECT_EQ(config.setup.camera.height, 480);
  EXPECT_DOUBLE_EQ(config.setup.camera.fy, 501);
  EXPECT_DOUBLE_EQ(config.setup.camera.cx, 319.5);
  EXPECT_EQ(config.setup.camera.model, LensModel::plumb_bob);
  EXPECT_DOUBLE_EQ(config.setup.camera.distortion[4], 0.0005);

  // `up`: the optical axis along base +z, image top (camera -y) toward the robot's front (+x).
  const Eigen::Matrix3d r_b_c = config.setup.mount.rotation;
  EXPECT_TRUE((r_b_c * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE((r_b_c * -Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(config.setup.mount.translation.isApprox(Eigen::Vector3d(0.1, 0, 0.3)));

  const MarkerMap& map = config.setup.map;
  ASSERT_EQ(map.dot_markers.size(), 2u);
  EXPECT_DOUBLE_EQ(map.dot_markers[0].pitch, 0.04);  // spec default
  EXPECT_DOUBLE_EQ(map.dot_markers[0].radius, 0.01);
  EXPECT_DOUBLE_EQ(map.dot_markers[1].pitch, 0.05);
  ASSERT_NE(map.find_dot_marker(7), nullptr);
  EXPECT_EQ(map.find_dot_marker(8), nullptr);
  ASSERT_EQ(map.square_markers.size(), 1u);
  EXPECT_DOUBLE_EQ(map.square_markers[0].dash, 0.10);
  EXPECT_TRUE(map.square_markers[0].corners[2].isApprox(Eigen::Vector3d(2, 2, 2.5)));
  ASSERT_EQ(map.led_landmarks.size(), 1u);
  EXPECT_TRUE(map.led_landmarks[0].direction->isApprox(-Eigen::Vector3d::UnitY()));
}

TEST_F(ConfigFiles, MountRpyIsAppliedOnTheBaseSide) {
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0, 0, 0], rpy: [0, 0, 1.5707963267948966]}
robot: {dof: 4}
map: map.yaml
)");
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.dof, Dof::height4);
  // R_B_C = Rz(pi/2) R_up: the image top now faces the robot's left (+y).
  EXPECT_TRUE((config.setup.mount.rotation * -Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitY()));
}

TEST_F(ConfigFiles, MountAsRotationMatrix) {
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {rotation: [0, -1, 0, 1, 0, 0, 0, 0, 1], xyz: [0, 0, 0.2]}
robot: {dof: 6}
map: map.yaml
)");
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.dof, Dof::full6);
  EXPECT_DOUBLE_EQ(config.setup.mount.rotation(0, 1), -1);
}

TEST_F(ConfigFiles, UnknownKeyIsNamedWithItsLine) {
  write("config.yaml", std::string(kConfig) + "mapp: x.yaml\n");
  EXPECT_EQ(config_error(), path("config.yaml") + ":7: mapp: unknown key");
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0, 0, 0.3], ryp: [0, 0, 0]}
robot: {dof: 3}
map: map.yaml
)");
  EXPECT_EQ(config_error(), path("config.yaml") + ":3: camera.mount.ryp: unknown key");
}

TEST_F(ConfigFiles, MalformedYamlNamesTheLine) {
  write("config.yaml", "camera:\n  calibration: [calib.yaml\nrobot: {dof: 3}\n");
  EXPECT_THAT(config_error(), StartsWith(path("config.yaml") + ":"));
  EXPECT_THAT(config_error(), HasSubstr("malformed YAML"));
}

TEST_F(ConfigFiles, BadValuesAreNamed) {
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0, 0, 0.3]}
robot: {dof: 5}
map: map.yaml
)");
  EXPECT_EQ(config_error(), path("config.yaml") + ":4: robot.dof: must be 3, 4 or 6, got 5");
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: down, xyz: [0, 0, 0.3]}
robot: {dof: 3}
map: map.yaml
)");
  EXPECT_EQ(config_error(), path("config.yaml") + ":3: camera.mount.preset: unknown preset 'down' (expected up)");
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {rotation: [1, 0, 0, 0, 1, 0, 0, 0, 2], xyz: [0, 0, 0.3]}
robot: {dof: 3}
map: map.yaml
)");
  EXPECT_THAT(config_error(), HasSubstr("camera.mount.rotation: not a rotation matrix"));
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0, zero, 0.3]}
robot: {dof: 3}
map: map.yaml
)");
  EXPECT_EQ(config_error(), path("config.yaml") + ":3: camera.mount.xyz: expected a finite number, got 'zero'");
  write("config.yaml", "camera:\n  calibration: calib.yaml\nrobot: {dof: 3}\nmap: map.yaml\n");
  EXPECT_EQ(config_error(), path("config.yaml") + ":2: camera.mount: required but missing");
}

TEST_F(ConfigFiles, ThePixelDepthAndTheSharedThresholdAreReadInTheirNewAndOldPlaces) {
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0, 0, 0.3]}
  pixel_bits: 12
robot: {dof: 3}
map: map.yaml
front_end: {threshold: 30, threshold_sigmas: 4, min_threshold: 9, threshold_rows: 24}
)");
  RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.dot.pixel_bits, 12);
  EXPECT_EQ(config.setup.dot.threshold, 30u);
  EXPECT_DOUBLE_EQ(config.setup.dot.threshold_sigmas, 4);
  EXPECT_EQ(config.setup.dot.min_threshold, 9u);
  EXPECT_EQ(config.setup.dot.threshold_rows, 24);
  // Configs written before the move still read the same.
  write("config.yaml", std::string(kConfig) + "dot: {pixel_bits: 10, threshold: 20, threshold_rows: 12}\n");
  config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.dot.pixel_bits, 10);
  EXPECT_EQ(config.setup.dot.threshold, 20u);
  EXPECT_EQ(config.setup.dot.threshold_rows, 12);
  // A key in both places is refused, naming where it moved.
  write("config.yaml", std::string(kConfig) + "front_end: {threshold: 30}\ndot:\n  threshold: 20\n");
  EXPECT_EQ(config_error(), path("config.yaml") + ":9: dot.threshold: moved to front_end.threshold, which the config gives too");
  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0, 0, 0.3]}
  pixel_bits: 12
robot: {dof: 3}
map: map.yaml
dot: {pixel_bits: 10}
)");
  EXPECT_EQ(config_error(), path("config.yaml") + ":7: dot.pixel_bits: moved to camera.pixel_bits, which the config gives too");
  write("config.yaml", std::string(kConfig) + "front_end: {pixel_bits: 10}\n");
  EXPECT_EQ(config_error(), path("config.yaml") + ":7: front_end.pixel_bits: unknown key");
}

TEST_F(ConfigFiles, TheOutsideInSectionIsReadOnlyInThatMode) {
  write("config.yaml", std::string(kConfig) + "outside_in: {track_gate_m: 0.5}\n");
  EXPECT_EQ(config_error(), path("config.yaml") + ":7: outside_in: only read with mode: outside_in");
}

TEST_F(ConfigFiles, TheMavlinkEkfOriginIsOptionalAndChecked) {
  EXPECT_FALSE(load_robot_config(dir_ / "config.yaml").ekf_origin);
  write("config.yaml", std::string(kConfig) + "mavlink:\n  ekf_origin: {latitude_deg: 47.3977419, longitude_deg: 8.5455938, altitude_m: 488}\n");
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  ASSERT_TRUE(config.ekf_origin);
  EXPECT_DOUBLE_EQ(config.ekf_origin->latitude_deg, 47.3977419);
  EXPECT_DOUBLE_EQ(config.ekf_origin->longitude_deg, 8.5455938);
  EXPECT_DOUBLE_EQ(config.ekf_origin->altitude_m, 488);
  write("config.yaml", std::string(kConfig) + "mavlink:\n  ekf_origin: {latitude_deg: 147, longitude_deg: 8, altitude_m: 0}\n");
  EXPECT_THAT(config_error(), HasSubstr("mavlink.ekf_origin.latitude_deg"));
  write("config.yaml", std::string(kConfig) + "mavlink:\n  origin: {}\n");
  EXPECT_THAT(config_error(), HasSubstr("mavlink.origin: unknown key"));
  write("config.yaml", std::string(kConfig) + "mavlink:\n  ekf_origin: {latitude_deg: 47, longitude_deg: 8}\n");
  EXPECT_THAT(config_error(), HasSubstr("mavlink.ekf_origin.altitude_m: required but missing"));
}

TEST_F(ConfigFiles, TheMavlinkPoseMessageIsOneOfTwo) {
  EXPECT_FALSE(load_robot_config(dir_ / "config.yaml").odometry);
  write("config.yaml", std::string(kConfig) + "mavlink:\n  pose_message: odometry\n");
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_TRUE(config.odometry);
  EXPECT_FALSE(config.ekf_origin);
  write("config.yaml", std::string(kConfig) + "mavlink:\n  pose_message: vision_position_estimate\n");
  EXPECT_FALSE(load_robot_config(dir_ / "config.yaml").odometry);
  write("config.yaml", std::string(kConfig) + "mavlink:\n  pose_message: odom\n");
  EXPECT_EQ(config_error(), path("config.yaml") + ":8: mavlink.pose_message: unknown message 'odom' (expected "
                                                   "vision_position_estimate or odometry)");
}

TEST_F(ConfigFiles, MissingFilesAreNamed) {
  write("config.yaml", std::string(kConfig).replace(std::string(kConfig).find("map.yaml"), 8, "nomap.yaml"));
  EXPECT_THAT(config_error(), StartsWith(path("nomap.yaml") + ": cannot open"));
  std::filesystem::remove(dir_ / "calib.yaml");
  EXPECT_THAT(config_error(), StartsWith(path("calib.yaml") + ": cannot open"));
  std::filesystem::remove(dir_ / "config.yaml");
  EXPECT_THAT(config_error(), StartsWith(path("config.yaml") + ": cannot open"));
}

TEST_F(ConfigFiles, CalibrationProblemsNameTheCalibrationFile) {
  std::string calibration = kCalibration;
  write("calib.yaml", calibration.replace(calibration.find("plumb_bob"), 9, "rational_polynomial"));
  EXPECT_EQ(config_error(), path("calib.yaml") +
                                ":8: distortion_model: unknown model 'rational_polynomial' (expected plumb_bob, "
                                "equidistant or equisolid)");
  calibration = kCalibration;
  write("calib.yaml", calibration.replace(calibration.find("cols: 5"), 7, "cols: 4"));
  EXPECT_THAT(config_error(), HasSubstr("distortion_coefficients.data: expected a list of 4 numbers"));
  write("calib.yaml", std::string(kCalibration) + "lens: wide\n");
  EXPECT_EQ(config_error(), path("calib.yaml") + ":17: lens: unknown key");
}

TEST(CalibrationFile, ReadsTheFisheyeModels) {
  test::TempDir dir;
  std::ofstream(dir / "fisheye.yaml") << R"(image_width: 1280
image_height: 1024
camera_matrix: {rows: 3, cols: 3, data: [400, 0, 640, 0, 400, 512, 0, 0, 1]}
distortion_model: equidistant
distortion_coefficients: {rows: 1, cols: 4, data: [0.1, -0.02, 0.003, -0.0004]}
)";
  const CameraIntrinsics fisheye = load_camera_info(dir / "fisheye.yaml");
  EXPECT_EQ(fisheye.model, LensModel::equidistant);
  EXPECT_DOUBLE_EQ(fisheye.distortion[3], -0.0004);

  std::ofstream(dir / "equisolid.yaml") << R"(image_width: 1280
image_height: 1024
camera_matrix: {rows: 3, cols: 3, data: [400, 0, 640, 0, 400, 512, 0, 0, 1]}
distortion_model: equisolid
distortion_coefficients: {rows: 1, cols: 0, data: []}
)";
  EXPECT_EQ(load_camera_info(dir / "equisolid.yaml").model, LensModel::equisolid);
}

TEST(MapFile, RejectsBadMarkers) {
  test::TempDir dir;
  const auto error_of = [&](const std::string& text) -> std::string {
    std::ofstream(dir / "map.yaml") << text;
    try {
      load_marker_map(dir / "map.yaml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string file = (dir / "map.yaml").string();
  EXPECT_EQ(error_of("dot_markers:\n  - id: 4096\n    origin: [0, 0, 2]\n    yaw: 0\n"),
            file + ":2: dot_markers[0].id: must be in [0, 4095], got 4096");
  EXPECT_EQ(error_of("dot_markers:\n  - {id: 3, origin: [0, 0, 2], yaw: 0}\n  - {id: 3, origin: [1, 0, 2], yaw: 0}\n"),
            file + ":2: dot_markers: id 3 appears twice (dot_markers[0] and [1])");
  // Duplicate landmarks, one rule for every kind (issue 32): an LED's name or position twice.
  EXPECT_EQ(error_of("led_landmarks:\n  - {name: A, position: [0, 0, 2]}\n  - {name: B, position: [1, 0, 2]}\n"
                     "  - {name: A, position: [2, 0, 2]}\n"),
            file + ":2: led_landmarks: name A appears twice (led_landmarks[0] and [2])");
  EXPECT_EQ(error_of("led_landmarks:\n  - {name: A, position: [0, 0.5, 2]}\n  - {name: B, position: [0, 0.5, 2]}\n"),
            file + ":2: led_landmarks: position [0, 0.5, 2] appears twice (led_landmarks[0] and [1])");
  EXPECT_EQ(error_of("dot_markers:\n  - {id: 3, origin: [0, 0, 2], yaw: 0, colour: red}\n"),
            file + ":2: dot_markers[0].colour: unknown key");
  EXPECT_EQ(error_of("square_markers:\n  - {name: a, corners: [[0, 0, 2], [2, 0, 2], [2, 2, 2]]}\n"),
            file + ":2: square_markers[0].corners: expected 4 corners [x, y, z], c0 -> c1 the solid side");
  EXPECT_EQ(error_of("led_landmarks:\n  - {name: L, position: [0, 0, 2], half_angle: 4}\n"),
            file + ":2: led_landmarks[0].half_angle: must be in [0.001, 3.141592653589793], got 4");
  EXPECT_EQ(error_of("dot_markers: []\n"),
            file + ":1: the map has no markers (expected dot_markers, square_markers or led_landmarks)");
}

// camera.line_time_ns (formats.md): absent is a global shutter; a rolling shutter's line time is
// read as given; a negative or absurd one is named.
TEST_F(ConfigFiles, LineTimeIsOptionalAndChecked) {
  EXPECT_EQ(load_robot_config(dir_ / "config.yaml").setup.line_time_ns, 0);
  const auto with_line_time = [&](const std::string& value) {
    write("config.yaml", "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0, 0, 0.3]}\n  line_time_ns: " +
                             value + "\nrobot: {dof: 3}\nmap: map.yaml\n");
  };
  with_line_time("37800");
  EXPECT_EQ(load_robot_config(dir_ / "config.yaml").setup.line_time_ns, 37800);
  with_line_time("0");
  EXPECT_EQ(load_robot_config(dir_ / "config.yaml").setup.line_time_ns, 0);
  with_line_time("-1");
  EXPECT_EQ(config_error(), path("config.yaml") + ":4: camera.line_time_ns: must be in [0, 1000000], got -1");
  with_line_time("37.8e3us");
  EXPECT_THAT(config_error(), StartsWith(path("config.yaml") + ":4: camera.line_time_ns: "));
}

// robot.max_speed and robot.max_yaw_rate (the fastest robot, for the rolling shutter): 1 m/s and
// 90 deg/s when absent; a robot's own figures are read; out of range is named.
TEST_F(ConfigFiles, TheFastestRobotIsOptionalAndChecked) {
  const MotionLimits absent = load_robot_config(dir_ / "config.yaml").setup.robot_limits;
  EXPECT_EQ(absent.speed, 1.0);
  EXPECT_NEAR(absent.yaw_rate, 3.14159265358979 / 2, 1e-9);
  const auto with_robot = [&](const std::string& robot) {
    write("config.yaml", "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0, 0, 0.3]}\nrobot: " + robot +
                             "\nmap: map.yaml\n");
  };
  with_robot("{dof: 3, max_speed: 2.5, max_yaw_rate: 4}");
  const MotionLimits given = load_robot_config(dir_ / "config.yaml").setup.robot_limits;
  EXPECT_EQ(given.speed, 2.5);
  EXPECT_EQ(given.yaw_rate, 4);
  with_robot("{dof: 3, max_speed: 0}");
  EXPECT_EQ(config_error(), path("config.yaml") + ":4: robot.max_speed: must be in [0.01, 100], got 0");
}

// robot.max_side_speed (the base origin's fastest sideways drive): absent, the robot may drive
// sideways as fast as ahead; given, at most max_speed.
TEST_F(ConfigFiles, TheSideSpeedIsOptionalAndAtMostTheSpeed) {
  const MotionLimits absent = load_robot_config(dir_ / "config.yaml").setup.robot_limits;
  EXPECT_FALSE(absent.side_speed);
  EXPECT_EQ(fastest_side_speed(absent), 1.0);
  const auto with_robot = [&](const std::string& robot) {
    write("config.yaml", "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0, 0, 0.3]}\nrobot: " + robot +
                             "\nmap: map.yaml\n");
  };
  with_robot("{dof: 3, max_speed: 2.5}");
  EXPECT_EQ(fastest_side_speed(load_robot_config(dir_ / "config.yaml").setup.robot_limits), 2.5);
  with_robot("{dof: 3, max_side_speed: 0.05}");
  const MotionLimits given = load_robot_config(dir_ / "config.yaml").setup.robot_limits;
  EXPECT_EQ(given.side_speed, 0.05);
  EXPECT_EQ(fastest_side_speed(given), 0.05);
  with_robot("{dof: 3, max_speed: 0.5, max_side_speed: 0.8}");
  EXPECT_EQ(config_error(), path("config.yaml") + ":4: robot.max_side_speed: must be at most max_speed (0.5), got 0.8");
  with_robot("{dof: 3, max_side_speed: 0}");
  EXPECT_EQ(config_error(), path("config.yaml") + ":4: robot.max_side_speed: must be in [0.01, 100], got 0");
}

// Finite but absurd numbers: each has a physical range, checked before anything is built from it.
TEST_F(ConfigFiles, AbsurdNumbersAreOutOfRange) {
  const auto calibration_error = [&](const std::string& from, const std::string& to) {
    std::string text = kCalibration;
    write("calib.yaml", text.replace(text.find(from), from.size(), to));
    return config_error();
  };
  EXPECT_EQ(calibration_error("data: [500, 0", "data: [1e12, 0"),
            path("calib.yaml") + ":5: camera_matrix: fx: must be in [1, 100000], got 1e+12");
  EXPECT_EQ(calibration_error("501, 239.5", "501, 4800"), path("calib.yaml") + ":5: camera_matrix: cy: must be in [-1920, 2400], got 4800");
  EXPECT_EQ(calibration_error("image_width: 640\nimage_height: 480", "image_width: 16384\nimage_height: 16384"),
            path("calib.yaml") + ":2: image_height: image_width x image_height must be at most 67108864 pixels, got 268435456");
  EXPECT_EQ(calibration_error("-0.1, 0.01", "-1e300, 0.01"),
            path("calib.yaml") + ":12: distortion_coefficients.data: must be in [-100, 100], got -1e+300");
  write("calib.yaml", kCalibration);

  write("config.yaml", R"(camera:
  calibration: calib.yaml
  mount: {preset: up, xyz: [0, 1e308, 0.3]}
robot: {dof: 3}
map: map.yaml
)");
  EXPECT_EQ(config_error(), path("config.yaml") + ":3: camera.mount.xyz: must be in [-10, 10], got 1e+308");
  write("config.yaml", kConfig);

  const auto map_error = [&](const std::string& map) {
    write("map.yaml", map);
    return config_error();
  };
  EXPECT_EQ(map_error("dot_markers:\n  - {id: 1, origin: [1e308, 0, 2.6], yaw: 0}\n"),
            path("map.yaml") + ":2: dot_markers[0].origin: must be in [-10000, 10000], got 1e+308");
  const std::string square = "square_markers:\n  - {name: a, corners: [[0, 0, 2], [2, 0, 2], [2, 2, 2], [0, 2, 2]], ";
  EXPECT_EQ(map_error(square + "tape_width: 1e-300}\n"),
            path("map.yaml") + ":2: square_markers[0].tape_width: must be in [0.005, 1], got 1e-300");
  EXPECT_EQ(map_error(square + "tape_width: 1e308}\n"),
            path("map.yaml") + ":2: square_markers[0].tape_width: must be in [0.005, 1], got 1e+308");
  EXPECT_EQ(map_error(square + "dash: 1e308}\n"), path("map.yaml") + ":2: square_markers[0].dash: must be in [0.01, 10], got 1e+308");
  EXPECT_EQ(map_error(square + "gap: 0}\n"), path("map.yaml") + ":2: square_markers[0].gap: must be in [0.01, 10], got 0");
}

}  // namespace
}  // namespace irloc::io
