// Erosion, dilation and the thin-line extractor against plain references.
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "algo/kernels/morphology.hpp"
#include "tests/kernels/reference_kernels.hpp"
#include "algo/kernels/thin_lines.hpp"
#include "tests/kernels/kernel_test_images.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::PaddedImage;

TEST(Morphology, MatchesReferenceForEveryShapeAndRadius) {
  std::mt19937 rng(21);
  Morphology morphology(128);
  const int sizes[][3] = {{1, 1, 0}, {2, 9, 1}, {17, 3, 0}, {33, 20, 5}, {40, 40, 3}, {127, 11, 1}};
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1], pad = size[2];
    for (const bool grey : {false, true}) {
      PaddedImage<std::uint8_t> in(w, h, pad);
      if (grey) test::fill_random(in, rng, 255);
      else test::fill_random_mask(in, rng, 70);
      for (const ElementShape shape : {ElementShape::square, ElementShape::cross}) {
        for (const int radius : {0, 1, 2, 3, 7}) {
          const StructuringElement element{shape, radius};
          PaddedImage<std::uint8_t> fast(w, h, pad, 0x33), slow(w, h, pad, 0x33);
          morphology.erode(in.view(), element, fast.view());
          reference::erode(in.view(), element, slow.view());
          ASSERT_EQ(fast.storage(), slow.storage()) << "erode " << w << "x" << h << " r" << radius;
          morphology.dilate(in.view(), element, fast.view());
          reference::dilate(in.view(), element, slow.view());
          ASSERT_EQ(fast.storage(), slow.storage()) << "dilate " << w << "x" << h << " r" << radius;
        }
      }
    }
  }
}

TEST(Morphology, ConstantImagesStayConstant) {
  Morphology morphology(50);
  PaddedImage<std::uint8_t> in(50, 30), out(50, 30);
  for (const std::uint8_t value : {std::uint8_t{0}, std::uint8_t{255}}) {
    in.fill(value);
    morphology.erode(in.view(), {ElementShape::square, 3}, out.view());
    EXPECT_EQ(out.at(0, 0), value);  // the border is ignored, not zero
    EXPECT_EQ(out.at(49, 29), value);
    morphology.dilate(in.view(), {ElementShape::cross, 3}, out.view());
    EXPECT_EQ(out.at(25, 15), value);
  }
}

TEST(ThinLines, KeepsTapeAndDropsLargeBrightAreas) {
  const int w = 120, h = 80;
  PaddedImage<std::uint8_t> image(w, h, 4), lines(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool tape = (y >= 20 && y < 23 && x >= 10 && x < 70) || (x >= 90 && x < 93 && y >= 5 && y < 75);
      const bool lamp = x >= 20 && x < 50 && y >= 40 && y < 70;
      image.at(x, y) = tape || lamp ? 200 : 15;
    }
  }
  ThinLineExtractor extractor(w, h, {ElementShape::square, 3});
  extractor.extract(image.view(), 100, lines.view());
  EXPECT_EQ(lines.at(40, 21), 255);  // horizontal tape, 3 px wide
  EXPECT_EQ(lines.at(91, 50), 255);  // vertical tape
  EXPECT_EQ(lines.at(35, 55), 0);    // lamp interior
  EXPECT_EQ(lines.at(20, 40), 0);    // lamp corner: the opening keeps a 30x30 square whole
  EXPECT_EQ(lines.at(100, 10), 0);   // background
  // Cross-check against binarize / erode / dilate / subtract with the references.
  PaddedImage<std::uint8_t> binary(w, h), eroded(w, h), opened(w, h);
  reference::threshold_binary<std::uint8_t>(image.view(), 100, 255, binary.view());
  reference::erode(binary.view(), {ElementShape::square, 3}, eroded.view());
  reference::dilate(eroded.view(), {ElementShape::square, 3}, opened.view());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      ASSERT_EQ(lines.at(x, y), binary.at(x, y) != 0 && opened.at(x, y) == 0 ? 255 : 0) << x << "," << y;
    }
  }
}

TEST(ThinLines, SixteenBitInputAndNoAllocation) {
  PaddedImage<std::uint16_t> image(64, 32);
  PaddedImage<std::uint8_t> lines(64, 32);
  for (int x = 0; x < 64; ++x) image.at(x, 10) = 3000;
  ThinLineExtractor extractor(64, 32, {ElementShape::cross, 2});
  test::AllocationCounter counter;
  extractor.extract(image.view(), 1000, lines.view());
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(lines.at(30, 10), 255);
  EXPECT_EQ(lines.at(30, 11), 0);
}

TEST(Morphology, AllocatesNothing) {
  Morphology morphology(64);
  PaddedImage<std::uint8_t> in(64, 64), out(64, 64);
  test::AllocationCounter counter;
  morphology.erode(in.view(), {ElementShape::square, 2}, out.view());
  morphology.dilate(in.view(), {ElementShape::cross, 2}, out.view());
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace irloc
