// MAVLink v2 framing: the checksum against the published CRC-16/MCRF4XX check value, the header
// layout, and payload truncation.

#include <array>
#include <cstdint>
#include <string_view>

#include <gtest/gtest.h>

#include "firmware/protocol/mavlink_frame.hpp"
#include "firmware/protocol/mavlink_messages.hpp"

namespace irloc::firmware {
namespace {

TEST(MavlinkCrc, MatchesTheCatalogueCheckValue) {
  // CRC-16/MCRF4XX of "123456789" is 0x6F91 (the CRC catalogue's check value).
  MavlinkCrc crc;
  for (const char c : std::string_view("123456789")) crc.add(static_cast<std::uint8_t>(c));
  EXPECT_EQ(crc.value(), 0x6F91);
}

TEST(MavlinkFrame, HeaderPayloadAndChecksumAreWhereTheSpecSays) {
  const std::array<std::uint8_t, 3> payload{7, 8, 9};
  std::array<std::uint8_t, kMavlink2MaxFrame> out{};
  const std::size_t size = encode_mavlink2(out, MavlinkAddress{42, 197}, 5, 0x012345, 77, payload);
  ASSERT_EQ(size, 10u + 3u + 2u);
  EXPECT_EQ(out[0], 0xFD);
  EXPECT_EQ(out[1], 3);   // payload length
  EXPECT_EQ(out[2], 0);   // incompat flags
  EXPECT_EQ(out[3], 0);   // compat flags
  EXPECT_EQ(out[4], 5);   // sequence
  EXPECT_EQ(out[5], 42);  // system
  EXPECT_EQ(out[6], 197); // component
  EXPECT_EQ(out[7], 0x45);
  EXPECT_EQ(out[8], 0x23);
  EXPECT_EQ(out[9], 0x01);
  EXPECT_EQ(out[10], 7);
  EXPECT_EQ(out[12], 9);
  MavlinkCrc crc;
  for (std::size_t i = 1; i < 13; ++i) crc.add(out[i]);
  crc.add(77);
  EXPECT_EQ(out[13], crc.value() & 0xFF);
  EXPECT_EQ(out[14], crc.value() >> 8);
}

TEST(MavlinkFrame, TrailingZerosAreTruncatedButOneByteStays) {
  std::array<std::uint8_t, kMavlink2MaxFrame> out{};
  const std::array<std::uint8_t, 5> trailing{1, 0, 2, 0, 0};
  EXPECT_EQ(encode_mavlink2(out, {}, 0, 1, 0, trailing), 10u + 3u + 2u);
  EXPECT_EQ(out[1], 3);
  const std::array<std::uint8_t, 4> zeros{};
  EXPECT_EQ(encode_mavlink2(out, {}, 0, 1, 0, zeros), 10u + 1u + 2u);
  EXPECT_EQ(out[1], 1);
}

TEST(MavlinkFrame, RefusesTooSmallAnOutput) {
  std::array<std::uint8_t, 12> out{};
  const std::array<std::uint8_t, 3> payload{1, 2, 3};
  EXPECT_EQ(encode_mavlink2(out, {}, 0, 1, 0, payload), 0u);
}

TEST(MavlinkMessages, VisionPositionEstimatePayloadIsLittleEndianInWireOrder) {
  VisionPositionEstimate message;
  message.usec = 0x0102030405060708ull;
  message.x = 1.0f;  // 0x3F800000
  message.covariance[20] = -2.0f;  // 0xC0000000
  message.reset_counter = 9;
  std::array<std::uint8_t, VisionPositionEstimate::kPayloadSize> out{};
  const auto payload = write_payload(message, out);
  ASSERT_EQ(payload.size(), 117u);
  EXPECT_EQ(payload[0], 0x08);
  EXPECT_EQ(payload[7], 0x01);
  EXPECT_EQ(payload[8 + 3], 0x3F);  // x, after usec
  EXPECT_EQ(payload[8 + 2], 0x80);
  EXPECT_EQ(payload[32 + 20 * 4 + 3], 0xC0);  // covariance[20], after the six floats
  EXPECT_EQ(payload[116], 9);                  // reset_counter last
}

TEST(MavlinkMessages, HeartbeatPayloadIsCustomModeFirst) {
  Heartbeat message;
  message.custom_mode = 0x11223344;
  std::array<std::uint8_t, Heartbeat::kPayloadSize> out{};
  const auto payload = write_payload(message, out);
  ASSERT_EQ(payload.size(), 9u);
  EXPECT_EQ(payload[0], 0x44);
  EXPECT_EQ(payload[3], 0x11);
  EXPECT_EQ(payload[4], 18);  // MAV_TYPE_ONBOARD_CONTROLLER
  EXPECT_EQ(payload[5], 8);   // MAV_AUTOPILOT_INVALID
  EXPECT_EQ(payload[8], 3);   // MAVLink version
}

}  // namespace
}  // namespace irloc::firmware
