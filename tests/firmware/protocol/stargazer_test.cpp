// StarGazer ASCII messages: exact text for known poses, and every message accepted by the
// pattern published with an independent StarGazer reader (pyStargazer's MAP_MODE_DATA_REGEX).

#include <numbers>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "firmware/protocol/stargazer_pose_stream.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::firmware {
namespace {

std::string text(std::span<const std::uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

MarkerMap ceiling() {
  MarkerMap map;
  DotMarker marker;
  marker.id = 1782;
  marker.origin = {1.0, 2.0, 2.6};
  map.dot_markers.push_back(marker);
  marker.id = 40;
  marker.origin = {3.0, 2.0, 3.0};
  map.dot_markers.push_back(marker);
  return map;
}

TEST(StarGazer, GoodPoseIsTheMapModeResultMessage) {
  StarGazerPoseStream stream(ceiling(), 0.3, "irloc test", 115200);
  PoseEstimate pose;
  pose.ok = true;
  pose.marker_id = 1782;
  pose.x = 1.2345;
  pose.y = -0.5;
  pose.z = 0.0;
  pose.yaw = -std::numbers::pi / 2;
  // height: 2.6 m marker - 0.3 m camera = 230 cm
  EXPECT_EQ(text(stream.encode(pose)), "~^I1782|-90.00|+123.45|-50.00|230.00`");
}

TEST(StarGazer, NoPoseIsDeadZone) {
  StarGazerPoseStream stream(ceiling(), 0.3, "irloc test", 115200);
  EXPECT_EQ(text(stream.encode(PoseEstimate{})), "~*DeadZone`");
}

TEST(StarGazer, OtherLandmarksReportIdZeroAndTheMeanCeilingHeight) {
  StarGazerPoseStream stream(ceiling(), 0.3, "irloc test", 115200);
  PoseEstimate pose;
  pose.ok = true;
  pose.marker_id = -1;
  pose.source = SourceKind::square;
  pose.yaw = std::numbers::pi;  // wrapped into (-pi, pi]: +180
  EXPECT_EQ(text(stream.encode(pose)), "~^I0|+180.00|+0.00|+0.00|250.00`");
}

TEST(StarGazer, EveryMessageMatchesTheIndependentReadersPattern) {
  const std::regex map_mode(R"(~\^I([0-9]+)\|([\+\-][0-9]+\.?[0-9]+)\|([\+\-][0-9]+\.?[0-9]+)\|([\+\-][0-9]+\.?[0-9]+)\|([0-9]+\.?[0-9]+)`)");
  StarGazerPoseStream stream(ceiling(), 0.3, "irloc test", 115200);
  for (int i = 0; i < 200; ++i) {
    PoseEstimate pose;
    pose.ok = true;
    pose.marker_id = i % 2 == 0 ? 40 : 1782;
    pose.x = -30.0 + 0.31 * i;
    pose.y = 12.0 - 0.17 * i;
    pose.yaw = -3.2 + 0.033 * i;
    const std::string message = text(stream.encode(pose));
    std::smatch fields;
    ASSERT_TRUE(std::regex_match(message, fields, map_mode)) << message;
    EXPECT_NEAR(std::stod(fields[3]), pose.x * 100, 0.005);
    EXPECT_NEAR(std::stod(fields[4]), pose.y * 100, 0.005);
  }
}

TEST(StarGazer, EncodingAllocatesNothing) {
  StarGazerPoseStream stream(ceiling(), 0.3, "irloc test", 115200);
  PoseEstimate pose;
  pose.ok = true;
  pose.marker_id = 40;
  test::AllocationCounter counter;
  std::size_t bytes = 0;
  for (int i = 0; i < 50; ++i) bytes += stream.encode(pose).size();
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(bytes, 0u);
}

}  // namespace
}  // namespace irloc::firmware
