#pragma once
// Turns each pose attempt into the bytes a serial pose-stream protocol sends (MAVLink v2 or
// StarGazer ASCII). Pure encoding: no OS, no allocation per call.

#include <cstdint>
#include <span>

#include "algo/pipeline/pose_estimate.hpp"

namespace irloc::firmware {

class PoseStreamEncoder {
 public:
  virtual ~PoseStreamEncoder() = default;
  // The bytes for this attempt (possibly none), in the encoder's own buffer: valid until the
  // next call. Attempts come in capture order.
  virtual std::span<const std::uint8_t> encode(const PoseEstimate& estimate) = 0;
};

}  // namespace irloc::firmware
