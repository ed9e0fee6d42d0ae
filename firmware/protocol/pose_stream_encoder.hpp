#pragma once
// One serial pose-stream protocol (MAVLink v2 or StarGazer ASCII): the bytes for each pose
// attempt, what it sends on its own clock whatever the camera does (a heartbeat), its answers to
// what the far end sends (commands, time sync), and the warnings irlocd prints, where the protocol
// carries text. Pure encoding: no OS, no allocation per call. Every call's bytes are in the
// encoder's own buffer, valid until its next call; the caller serialises the calls.

#include <cstdint>
#include <span>
#include <string_view>

#include "algo/pipeline/pose_estimate.hpp"

namespace irloc::firmware {

// What the link reports about irlocd (MAVLink's system_status).
enum class LinkHealth : std::uint8_t {
  starting,  // devices open, no frame yet
  active,    // frames arrive and the strobe is verified
  critical,  // the camera is lost, or the strobe pair was not verified
};

class PoseStreamEncoder {
 public:
  virtual ~PoseStreamEncoder() = default;
  // The bytes for this attempt (possibly none). Attempts come in capture order.
  virtual std::span<const std::uint8_t> encode(const PoseEstimate& estimate) = 0;
  // What is due at `now_ns` (CLOCK_MONOTONIC) on the link's own clock; called at least every 50 ms.
  virtual std::span<const std::uint8_t> tick(std::int64_t /*now_ns*/) { return {}; }
  // The answers to `bytes` received at `now_ns`; a message may arrive split over several calls.
  virtual std::span<const std::uint8_t> receive(std::span<const std::uint8_t> /*bytes*/, std::int64_t /*now_ns*/) {
    return {};
  }
  // A line for irlocd's log about the last receive() (a refused command); empty when none.
  virtual std::string_view receive_note() const { return {}; }
  // A warning irlocd printed (without its "irlocd: " prefix).
  virtual std::span<const std::uint8_t> warning(std::string_view /*text*/) { return {}; }
  virtual void set_health(LinkHealth /*health*/) {}
};

}  // namespace irloc::firmware
