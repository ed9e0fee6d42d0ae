#pragma once
// The StarGazer host commands a robot's driver sends on the sensor's RX line, answered as the
// sensor answers them (docs/hardware.md, "StarGazer host commands"). Messages are ASCII between
// `~` and a back-quote, and may arrive a byte at a time:
//   ~#CalcStop`  ~#CalcStart`  ~#SetEnd`  ~#Reset`         commands
//   ~@NAME`                                               a parameter read
//   ~#NAME|VALUE`                                         a parameter write
// Answers: a command or a write is acknowledged by echoing it with `!` (`~!CalcStop``,
// `~!MarkHeight|2500``); a read by `~!NAME`` and then `~$NAME|VALUE``; SetEnd and Reset by their
// acknowledgement and then `~!ParameterUpdate``. Writes are held until SetEnd, as on the sensor.
// A write irloc cannot honour, or an unknown name, gets no acknowledgement (the driver's retries
// run out and it reports the parameter) but `~*Refused|NAME`` and a reason for irlocd's stderr.
// Allocates nothing per byte.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace irloc::firmware {

// The parameters as irloc has them. Numbers are decimal text on the wire.
struct StarGazerParameters {
  std::string_view version;   // read only
  int baud_rate = 115200;     // the serial link's; a write must keep it (the board file sets it)
  int id_count = 0;           // IDNum: the dot markers in the map; set by the map, not by a write
  int reference_id = 0;       // RefID: the map's lowest dot marker ID; set by the map
  bool height_fixed = false;  // HeightFix: report mark_height_mm as the height instead of the map's
  int mark_height_mm = 0;     // MarkHeight: landmark height above the camera (the map's, or written)
};

class StarGazerHostCommands {
 public:
  explicit StarGazerHostCommands(const StarGazerParameters& defaults);

  // The answers to `bytes`; valid until the next call.
  std::span<const std::uint8_t> receive(std::span<const std::uint8_t> bytes);
  // Why the last call refused a message (the last one when several were); empty when none was.
  std::string_view last_refusal() const { return {refusal_.data(), refusal_size_}; }

  // Pose results are sent only while calculating: from start-up, and between CalcStart and CalcStop.
  bool calculating() const { return calculating_; }
  const StarGazerParameters& parameters() const { return committed_; }

 private:
  void handle(std::string_view message);
  void handle_write(std::string_view name, std::string_view value);
  void handle_read(std::string_view name);
  void answer(std::string_view kind, std::string_view name, std::string_view value = {});
  void refuse(std::string_view name, std::string_view reason);

  StarGazerParameters defaults_;
  StarGazerParameters committed_;
  StarGazerParameters pending_;
  bool calculating_ = true;
  std::array<char, 64> message_{};
  std::size_t message_size_ = 0;
  bool in_message_ = false;
  std::array<std::uint8_t, 512> out_{};
  std::size_t out_size_ = 0;
  std::array<char, 160> refusal_{};
  std::size_t refusal_size_ = 0;
};

}  // namespace irloc::firmware
