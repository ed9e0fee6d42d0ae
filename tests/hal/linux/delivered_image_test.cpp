// The grey image read out of each pixel format libcamera may deliver, with rows padded beyond the
// image (as an ISP pads them): OpenCV's own conversions are the oracle where it has one; the
// packed 10-bit layout is checked by packing known values as MIPI CSI-2 RAW10 does.

#include "hal/linux/delivered_image.hpp"

#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "tests/support/allocation_counter.hpp"

namespace irloc::hal {
namespace {

constexpr int kWidth = 82;  // not a multiple of 4 or 8: the last group of packed pixels is partial
constexpr int kHeight = 6;
constexpr std::uint8_t kPadding = 0xA5;

// A buffer of `rows` rows of `stride` bytes: random image bytes, the padding after each row's
// `row_bytes` set to kPadding (a reader that steps by the width would read it).
std::vector<std::uint8_t> padded_buffer(int rows, std::size_t row_bytes, std::size_t stride, unsigned seed) {
  std::vector<std::uint8_t> buffer(static_cast<std::size_t>(rows) * stride, kPadding);
  std::mt19937 random(seed);
  for (int y = 0; y < rows; ++y) {
    for (std::size_t x = 0; x < row_bytes; ++x) buffer[static_cast<std::size_t>(y) * stride + x] = static_cast<std::uint8_t>(random());
  }
  return buffer;
}

template <typename View>
cv::Mat as_mat(const View& view, int type) {
  cv::Mat out(view.height(), view.width(), type);
  for (int y = 0; y < view.height(); ++y) {
    for (int x = 0; x < view.width(); ++x) {
      if (type == CV_8UC1) out.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(view.at(x, y));
      else out.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(view.at(x, y));
    }
  }
  return out;
}

bool equal(const cv::Mat& a, const cv::Mat& b) { return a.size() == b.size() && cv::countNonZero(a != b) == 0; }

GrayImageView read(PixelLayout layout, const std::vector<std::uint8_t>& buffer, std::size_t stride, ConvertedImage& converted) {
  test::AllocationCounter counter;
  const GrayImageView image = grey_image(layout, buffer.data(), kWidth, kHeight, stride, converted);
  EXPECT_EQ(counter.count(), 0u);
  return image;
}

TEST(DeliveredImage, Nv12IsItsLumaPlaneReadWithTheStride) {
  const std::size_t stride = 96;
  const std::vector<std::uint8_t> buffer = padded_buffer(kHeight * 3 / 2, kWidth, stride, 1);
  ConvertedImage converted = converted_image_for(PixelLayout::y_plane, kWidth, kHeight);
  const GrayImageView image = read(PixelLayout::y_plane, buffer, stride, converted);
  cv::Mat expected;
  cv::cvtColor(cv::Mat(kHeight * 3 / 2, kWidth, CV_8UC1, const_cast<std::uint8_t*>(buffer.data()), stride), expected,
               cv::COLOR_YUV2GRAY_NV12);
  ASSERT_TRUE(std::holds_alternative<ImageView8>(image));
  EXPECT_TRUE(equal(as_mat(std::get<ImageView8>(image), CV_8UC1), expected));
}

TEST(DeliveredImage, YuyvIsItsLumaBytesReadWithTheStride) {
  const std::size_t stride = 2 * kWidth + 28;
  const std::vector<std::uint8_t> buffer = padded_buffer(kHeight, 2 * kWidth, stride, 2);
  ConvertedImage converted = converted_image_for(PixelLayout::yuyv, kWidth, kHeight);
  const GrayImageView image = read(PixelLayout::yuyv, buffer, stride, converted);
  cv::Mat expected;
  cv::cvtColor(cv::Mat(kHeight, kWidth, CV_8UC2, const_cast<std::uint8_t*>(buffer.data()), stride), expected,
               cv::COLOR_YUV2GRAY_YUYV);
  ASSERT_TRUE(std::holds_alternative<ImageView8>(image));
  EXPECT_TRUE(equal(as_mat(std::get<ImageView8>(image), CV_8UC1), expected));
}

TEST(DeliveredImage, Mono8AndMono16AreReadInPlaceWithTheStride) {
  const std::size_t stride8 = kWidth + 14;
  const std::vector<std::uint8_t> buffer8 = padded_buffer(kHeight, kWidth, stride8, 3);
  ConvertedImage none = converted_image_for(PixelLayout::mono8, kWidth, kHeight);
  const GrayImageView image8 = read(PixelLayout::mono8, buffer8, stride8, none);
  ASSERT_TRUE(std::holds_alternative<ImageView8>(image8));
  EXPECT_EQ(std::get<ImageView8>(image8).data(), buffer8.data());
  EXPECT_TRUE(equal(as_mat(std::get<ImageView8>(image8), CV_8UC1),
                    cv::Mat(kHeight, kWidth, CV_8UC1, const_cast<std::uint8_t*>(buffer8.data()), stride8)));

  const std::size_t stride16 = 2 * kWidth + 12;
  const std::vector<std::uint8_t> buffer16 = padded_buffer(kHeight, 2 * kWidth, stride16, 4);
  const GrayImageView image16 = read(PixelLayout::mono16, buffer16, stride16, none);
  ASSERT_TRUE(std::holds_alternative<ImageView16>(image16));
  EXPECT_TRUE(equal(as_mat(std::get<ImageView16>(image16), CV_16UC1),
                    cv::Mat(kHeight, kWidth, CV_16UC1, const_cast<std::uint8_t*>(buffer16.data()), stride16)));
}

TEST(DeliveredImage, PackedRaw10GivesBackTheTenBitValuesPackedIntoIt) {
  // MIPI CSI-2 RAW10: each group of 4 pixels is their high 8 bits in 4 bytes, then a byte holding
  // their low 2 bits, pixel 0 in bits 1..0. The last group of a row may be partial.
  const std::size_t row_bytes = (kWidth + 3) / 4 * 5;
  const std::size_t stride = row_bytes + 9;
  std::vector<std::uint8_t> buffer(kHeight * stride, kPadding);
  std::vector<std::uint16_t> values(kWidth * kHeight);
  std::mt19937 random(5);
  for (int y = 0; y < kHeight; ++y) {
    std::uint8_t* row = buffer.data() + y * stride;
    for (std::size_t group = 0; group < row_bytes / 5; ++group) row[group * 5 + 4] = 0;
    for (int x = 0; x < kWidth; ++x) {
      const auto value = static_cast<std::uint16_t>(random() % 1024);
      values[y * kWidth + x] = value;
      row[(x / 4) * 5 + x % 4] = static_cast<std::uint8_t>(value >> 2);
      row[(x / 4) * 5 + 4] |= static_cast<std::uint8_t>((value & 0x3) << (2 * (x % 4)));
    }
  }
  ConvertedImage converted = converted_image_for(PixelLayout::packed10, kWidth, kHeight);
  const GrayImageView image = read(PixelLayout::packed10, buffer, stride, converted);
  ASSERT_TRUE(std::holds_alternative<ImageView16>(image));
  const ImageView16& view = std::get<ImageView16>(image);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) ASSERT_EQ(view.at(x, y), values[y * kWidth + x]) << "pixel " << x << ", " << y;
  }
}

TEST(DeliveredImage, EachFormatHasItsLayout) {
  EXPECT_EQ(pixel_layout_of("R8"), PixelLayout::mono8);
  for (const char* format : {"R10", "R12", "R16"}) EXPECT_EQ(pixel_layout_of(format), PixelLayout::mono16);
  EXPECT_EQ(pixel_layout_of("R10_CSI2P"), PixelLayout::packed10);
  EXPECT_EQ(pixel_layout_of("YUV420"), PixelLayout::y_plane);
  EXPECT_EQ(pixel_layout_of("NV12"), PixelLayout::y_plane);
  EXPECT_EQ(pixel_layout_of("YUYV"), PixelLayout::yuyv);
}

}  // namespace
}  // namespace irloc::hal
