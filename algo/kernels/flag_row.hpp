#pragma once
// The fused front end's pass over one row of a frame pair. Internal to algo/kernels.

#include <cstdint>

namespace irloc::detail {

// Flags are summarised per chunk of 32 bytes: 32 8-bit or 16 16-bit pixels.
template <typename Pixel>
inline constexpr int kPixelsPerChunk = static_cast<int>(32 / sizeof(Pixel));

// flags[i] = max(on[i] - off[i] - threshold, 0) for i < n: nonzero exactly where the strobe
// difference is above the threshold; chunks[c] = 1 if any flag of chunk c (pixels
// [c * kPixelsPerChunk, (c + 1) * kPixelsPerChunk) within n) is set, else 0. Returns whether any
// flag is set.
bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n, std::uint8_t threshold,
                           std::uint8_t* flags, std::uint8_t* chunks);
bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n, std::uint16_t threshold,
                           std::uint16_t* flags, std::uint8_t* chunks);

}  // namespace irloc::detail
