#pragma once
// The grey image in a frame buffer as libcamera delivers it: the pixel formats the camera backend
// takes, and how each holds the image. Rows are `stride` bytes apart, at least a row's own bytes
// (an ISP pads rows: the Raspberry Pi's to 64 bytes, so 820 pixels of R8 take 832). No libcamera
// here: the layouts are tested on their own (tests/hal/linux/delivered_image_test.cpp).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "algo/core/image_view.hpp"

namespace irloc::hal {

enum class PixelLayout {
  mono8,     // R8: one byte a pixel
  mono16,    // R10, R12, R16: one 16-bit word a pixel, the value in its low bits
  packed10,  // R10_CSI2P (MIPI CSI-2 RAW10): four pixels' high 8 bits, then one byte of their low 2-bit pairs
  y_plane,   // YUV420, NV12: the first plane is the luma
  yuyv,      // YUYV: Y0 U Y1 V
};

// The pixel formats by name, best first (the backend's default order of preference).
inline const std::vector<std::string> kDeliveredFormats = {"R8", "R10", "R12", "R16", "R10_CSI2P", "YUV420", "NV12", "YUYV"};

// Of a format in kDeliveredFormats.
PixelLayout pixel_layout_of(const std::string& format);

// Room for the image of a layout that is not a grey image in place (YUYV, packed 10-bit), sized at
// start-up.
struct ConvertedImage {
  std::vector<std::uint8_t> pixels8;
  std::vector<std::uint16_t> pixels16;
};
ConvertedImage converted_image_for(PixelLayout layout, int width, int height);

// The width x height grey image in `pixels` (the buffer's first plane, rows `stride` bytes apart):
// a view of it in place, or of its copy in `converted` (made by converted_image_for). Allocates
// nothing.
GrayImageView grey_image(PixelLayout layout, const std::uint8_t* pixels, int width, int height, std::size_t stride,
                         ConvertedImage& converted);

}  // namespace irloc::hal
