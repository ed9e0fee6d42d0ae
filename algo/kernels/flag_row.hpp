#pragma once
// The fused front end's pass over one row of a frame pair. Internal to algo/kernels.

#include <cstdint>

#include "algo/kernels/strobe_check.hpp"

namespace irloc::detail {

// flags[i] = max(on[i] - off[i] - threshold, 0) for i < n: nonzero exactly where the strobe
// difference is above the threshold. Returns whether any flag is set.
bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n, std::uint8_t threshold,
                           std::uint8_t* flags);
bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n, std::uint16_t threshold,
                           std::uint16_t* flags);

// The same, and in the same pass adds to strobe the pixels with on - off > noise_level and
// off - on > noise_level (the strobe check's evidence).
bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n, std::uint8_t threshold,
                           std::uint8_t noise_level, std::uint8_t* flags, StrobeCounts& strobe);
bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n, std::uint16_t threshold,
                           std::uint16_t noise_level, std::uint16_t* flags, StrobeCounts& strobe);

}  // namespace irloc::detail
