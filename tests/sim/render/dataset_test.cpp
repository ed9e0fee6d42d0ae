// Rendered datasets: deterministic for a seed, readable by irlocd's loaders, dropped frames left
// out, 8- and 12-bit output, and a truth row per frame.

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "io/config/config_file.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "tests/support/scenario_text.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::sim {
namespace {

std::string contents(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

test::ScenarioText noisy_moving(int seed) {
  test::ScenarioText text;
  text.noise = true;
  text.seed = seed;
  text.frames = 6;
  text.trajectory = "  type: loop\n  centre: [0, 0]\n  radius: 0.2\n  speed: 0.3\n";
  text.room = "  ceiling_height: 1.3\n  ambient: 2\n";
  text.extra = "render:\n  supersampling: 2\n  motion_blur_samples: 2\npeople:\n  - {path: [[-1, 0.5], [1, 0.5]], speed: 1}\n";
  return text;
}

TEST(Dataset, SameSeedSameBytesOtherSeedOtherNoise) {
  const test::TempDir dir;
  render_dataset(parse_scenario(noisy_moving(5).yaml(), "a.yaml"), dir / "a");
  render_dataset(parse_scenario(noisy_moving(5).yaml(), "a.yaml"), dir / "b");
  render_dataset(parse_scenario(noisy_moving(6).yaml(), "a.yaml"), dir / "c");
  for (const char* file : {"frame_000000.pgm", "frame_000003.pgm", "truth.csv", "frames.csv"}) {
    EXPECT_EQ(contents(dir / "a" / file), contents(dir / "b" / file)) << file;
  }
  EXPECT_NE(contents(dir / "a" / "frame_000003.pgm"), contents(dir / "c" / "frame_000003.pgm"));
}

TEST(Dataset, IrlocdLoadersReadTheWrittenConfig) {
  const test::TempDir dir;
  test::ScenarioText text;
  text.map += "  square_markers:\n    - name: \"hall: \\\"B\\\" #2\"\n      corners: [[-1, -1, 1.3], [1, -1, 1.3], [1, 1, 1.3], [-1, 1, 1.3]]\n"
              "  led_landmarks:\n    - {name: L1, position: [2, 0, 1.2], direction: [-1, 0, 0], half_angle: 0.8}\n";
  const Scenario scenario = parse_scenario(text.yaml(), "config.yaml");
  render_dataset(scenario, dir.path());
  const io::RobotConfig config = io::load_robot_config(dir / "config.yaml");
  EXPECT_EQ(config.setup.camera.width, 48);
  EXPECT_EQ(config.setup.camera.fx, scenario.camera.intrinsics.fx);
  EXPECT_TRUE(to_isometry(config.setup.mount).isApprox(scenario.camera.mount, 1e-12));
  ASSERT_EQ(config.setup.map.dot_markers.size(), 1u);
  EXPECT_EQ(config.setup.map.dot_markers[0].id, 1782);
  EXPECT_EQ(config.setup.map.dot_markers[0].yaw, 0.4);
  ASSERT_EQ(config.setup.map.square_markers.size(), 1u);
  EXPECT_EQ(config.setup.map.square_markers[0].name, "hall: \"B\" #2");
  ASSERT_EQ(config.setup.map.led_landmarks.size(), 1u);
  EXPECT_EQ(*config.setup.map.led_landmarks[0].half_angle, 0.8);
}

TEST(Dataset, DroppedFramesAreLeftOutAndTruthFollowsTheFrames) {
  const test::TempDir dir;
  test::ScenarioText text;
  text.frames = 8;
  text.trajectory = "  type: spin\n  centre: [0, 0]\n  rate: 1.5\n";
  text.extra = "render:\n  supersampling: 1\ndropped_frames:\n  seqs: [3]\n";
  text.calibration += "  frame_rate: 20\n";  // ends the calibration block; a camera key
  const Scenario scenario = parse_scenario(text.yaml(), "drop.yaml");
  const std::vector<TruthRow> written = render_dataset(scenario, dir.path());
  const std::vector<TruthRow> truth = read_truth_csv(dir / "truth.csv");
  ASSERT_EQ(truth.size(), 7u);
  ASSERT_EQ(written.size(), 7u);
  for (const TruthRow& row : truth) EXPECT_NE(row.seq, 3u);
  EXPECT_FALSE(std::filesystem::exists(dir / "frame_000003.pgm"));
  EXPECT_EQ(truth[4].seq, 5u);
  EXPECT_EQ(truth[4].t_ns, 1'000'000'000 + 5 * 50'000'000);
  EXPECT_NEAR(truth[4].yaw, 1.5 * 0.25, 1e-9);
  const std::string index = contents(dir / "frames.csv");
  EXPECT_NE(index.find("4,1200000000,1,frame_000004.pgm"), std::string::npos) << index;
  EXPECT_NE(index.find("5,1250000000,0,frame_000005.pgm"), std::string::npos) << index;
}

TEST(Dataset, TwelveBitFramesUseMaxval4095) {
  const test::TempDir dir;
  test::ScenarioText text;
  text.calibration += "  bit_depth: 12\n";
  render_dataset(parse_scenario(text.yaml(), "twelve.yaml"), dir.path());
  EXPECT_EQ(contents(dir / "frame_000000.pgm").substr(0, 14), "P5\n48 36\n4095\n");
}

}  // namespace
}  // namespace irloc::sim
