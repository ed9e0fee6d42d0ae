#pragma once
// The pose-stream link: the frame loop's pose attempts, and, on a thread of its own, what the
// protocol sends on its own clock (MAVLink's 1 Hz HEARTBEAT, whatever the camera does) and its
// answers to what the far end sends (StarGazer host commands, MAVLink TIMESYNC). One lock orders
// every use of the port and the encoder, so messages never interleave. The thread polls the
// port's receive descriptor at least every 50 ms; it allocates nothing once started.

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>

#include "firmware/protocol/pose_stream_encoder.hpp"
#include "firmware/warning_log.hpp"
#include "hal/serial_port.hpp"

namespace irloc::firmware {

class SerialLink final : public WarningListener {
 public:
  // `log` gets a line for each command the protocol refused. Starts the thread.
  SerialLink(hal::SerialPort& port, PoseStreamEncoder& encoder, std::FILE* log);
  ~SerialLink() override;  // stops the thread
  SerialLink(const SerialLink&) = delete;
  SerialLink& operator=(const SerialLink&) = delete;

  // Sends one attempt's bytes; the CLOCK_MONOTONIC time (ns) of the write, or empty when the
  // attempt has none or the port dropped them.
  std::optional<std::int64_t> send_attempt(const PoseEstimate& estimate);
  void warning(std::string_view text) override;
  void set_health(LinkHealth health);

  // The port, under the link's lock.
  bool connected();
  std::uint64_t messages_dropped();
  int last_error();
  void reopen_now();

  static std::int64_t now_ns();

 private:
  void run();
  void serve(bool input_ready);
  void write(std::span<const std::uint8_t> bytes);

  hal::SerialPort& port_;
  PoseStreamEncoder& encoder_;
  std::FILE* log_;
  std::mutex mutex_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace irloc::firmware
