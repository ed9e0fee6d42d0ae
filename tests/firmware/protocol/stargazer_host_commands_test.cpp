// The StarGazer host commands as the public drivers send them (pyStargazer's send_command,
// read_parameter, write_parameter, save_settings, reset: `~#`/`~@` messages, answered by `~!`
// acknowledgements, `~$` values and `~!ParameterUpdate``), byte by byte as they type them; pose
// results stop between CalcStop and CalcStart; refused writes are not acknowledged.

#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "firmware/protocol/stargazer_pose_stream.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::firmware {
namespace {

std::string text(std::span<const std::uint8_t> bytes) { return {bytes.begin(), bytes.end()}; }

std::span<const std::uint8_t> bytes_of(const std::string& message) {
  return {reinterpret_cast<const std::uint8_t*>(message.data()), message.size()};
}

// What the stream answers to `message` sent one byte at a time (the drivers pause 10 ms between
// characters, so every byte is a read of its own).
std::string answer_bytewise(StarGazerPoseStream& stream, const std::string& message) {
  std::string answers;
  for (std::size_t i = 0; i < message.size(); ++i) answers += text(stream.receive(bytes_of(message).subspan(i, 1), 0));
  return answers;
}

MarkerMap two_markers() {
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

PoseEstimate pose_under_1782() {
  PoseEstimate pose;
  pose.ok = true;
  pose.marker_id = 1782;
  pose.x = 1.0;
  pose.yaw = std::numbers::pi / 2;
  return pose;
}

TEST(StarGazerHostCommands, ADriversStartUpSequenceIsAnsweredAsTheSensorAnswersIt) {
  StarGazerPoseStream stream(two_markers(), 0.3, "irloc 0.1.0", 115200);
  EXPECT_EQ(answer_bytewise(stream, "~#CalcStop`"), "~!CalcStop`");
  EXPECT_TRUE(stream.encode(pose_under_1782()).empty());  // no result while stopped
  EXPECT_TRUE(stream.encode(PoseEstimate{}).empty());
  EXPECT_EQ(answer_bytewise(stream, "~@Version`"), "~!Version`~$Version|irloc 0.1.0`");
  EXPECT_EQ(answer_bytewise(stream, "~@BaudRate`"), "~!BaudRate`~$BaudRate|115200`");
  EXPECT_EQ(answer_bytewise(stream, "~@IDNum`"), "~!IDNum`~$IDNum|2`");
  EXPECT_EQ(answer_bytewise(stream, "~@RefID`"), "~!RefID`~$RefID|40`");
  EXPECT_EQ(answer_bytewise(stream, "~@HeightFix`"), "~!HeightFix`~$HeightFix|No`");
  // The mean ceiling height above the camera: (2.6 + 3.0) / 2 - 0.3 = 2.5 m.
  EXPECT_EQ(answer_bytewise(stream, "~@MarkHeight`"), "~!MarkHeight`~$MarkHeight|2500`");
  EXPECT_EQ(answer_bytewise(stream, "~@MarkMode`"), "~!MarkMode`~$MarkMode|Map`");
  EXPECT_EQ(answer_bytewise(stream, "~#MarkHeight|2400`"), "~!MarkHeight|2400`");
  EXPECT_EQ(answer_bytewise(stream, "~#HeightFix|Yes`"), "~!HeightFix|Yes`");
  EXPECT_EQ(answer_bytewise(stream, "~#MarkMode|Map`"), "~!MarkMode|Map`");
  EXPECT_EQ(answer_bytewise(stream, "~#BaudRate|115200`"), "~!BaudRate|115200`");
  EXPECT_EQ(answer_bytewise(stream, "~@MarkHeight`"), "~!MarkHeight`~$MarkHeight|2500`");  // not before SetEnd
  EXPECT_EQ(answer_bytewise(stream, "~#SetEnd`"), "~!SetEnd`~!ParameterUpdate`");
  EXPECT_EQ(answer_bytewise(stream, "~@MarkHeight`"), "~!MarkHeight`~$MarkHeight|2400`");
  EXPECT_EQ(answer_bytewise(stream, "~#CalcStart`"), "~!CalcStart`");
  // HeightFix Yes: the written MarkHeight is the height, in centimetres.
  EXPECT_EQ(text(stream.encode(pose_under_1782())), "~^I1782|+90.00|+100.00|+0.00|240.00`");
}

TEST(StarGazerHostCommands, WritesIrlocCannotHonourAreRefusedWithoutAcknowledgement) {
  StarGazerPoseStream stream(two_markers(), 0.3, "irloc 0.1.0", 115200);
  EXPECT_EQ(text(stream.receive(bytes_of("~#MarkType|HLD1L`"), 0)), "~*Refused|MarkType`");
  EXPECT_EQ(stream.receive_note(),
            "StarGazer host command MarkType refused: irloc's markers are its own (dot, square, LED), set by its map file");
  EXPECT_EQ(text(stream.receive(bytes_of("~#BaudRate|9600`"), 0)), "~*Refused|BaudRate`");
  EXPECT_EQ(text(stream.receive(bytes_of("~#IDNum|4`"), 0)), "~*Refused|IDNum`");
  EXPECT_EQ(text(stream.receive(bytes_of("~#RefID|7`"), 0)), "~*Refused|RefID`");
  EXPECT_EQ(text(stream.receive(bytes_of("~#MarkMode|Alone`"), 0)), "~*Refused|MarkMode`");
  EXPECT_EQ(text(stream.receive(bytes_of("~#MarkHeight|tall`"), 0)), "~*Refused|MarkHeight`");
  EXPECT_EQ(text(stream.receive(bytes_of("~#HeightCalc`"), 0)), "~*Refused|HeightCalc`");
  EXPECT_EQ(text(stream.receive(bytes_of("~@Colour`"), 0)), "~*Refused|Colour`");
  EXPECT_EQ(text(stream.receive(bytes_of("~#IDNum|2`"), 0)), "~!IDNum|2`");  // what irloc has is fine
  EXPECT_TRUE(stream.receive_note().empty());
}

TEST(StarGazerHostCommands, ResetRestoresIrlocsValuesAndNoiseIsIgnored) {
  StarGazerPoseStream stream(two_markers(), 0.3, "irloc 0.1.0", 115200);
  text(stream.receive(bytes_of("~#HeightFix|Yes`~#MarkHeight|1000`~#SetEnd`"), 0));
  EXPECT_EQ(text(stream.receive(bytes_of("~@HeightFix`"), 0)), "~!HeightFix`~$HeightFix|Yes`");
  EXPECT_EQ(text(stream.receive(bytes_of("~#Reset`"), 0)), "~!Reset`~!ParameterUpdate`");
  EXPECT_EQ(text(stream.receive(bytes_of("~@HeightFix`"), 0)), "~!HeightFix`~$HeightFix|No`");
  // Line noise, an unfinished message cut by a new one, and an over-long one: only the whole
  // message is answered.
  EXPECT_EQ(text(stream.receive(bytes_of("\r\n~#Calc~#CalcStop`~#" + std::string(100, 'x') + "`"), 0)), "~!CalcStop`");
  EXPECT_FALSE(stream.host_commands().calculating());
}

TEST(StarGazerHostCommands, AnsweringAllocatesNothing) {
  StarGazerPoseStream stream(two_markers(), 0.3, "irloc 0.1.0", 115200);
  const std::string session = "~#CalcStop`~@Version`~#MarkHeight|2500`~#SetEnd`~#MarkType|x`~#CalcStart`";
  test::AllocationCounter counter;
  std::size_t bytes = 0;
  for (int i = 0; i < 20; ++i) bytes += stream.receive(bytes_of(session), 0).size();
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(bytes, 0u);
}

}  // namespace
}  // namespace irloc::firmware
