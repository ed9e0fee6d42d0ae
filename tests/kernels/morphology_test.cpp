// Erosion, dilation and the thin-line extractor against plain references.
#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "algo/kernels/fused_front_end.hpp"
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

// lines == binary and not opened, with the plain references of threshold, erode and dilate.
template <typename Pixel>
void expect_matches_reference(const PaddedImage<Pixel>& on, const PaddedImage<Pixel>& off, Pixel threshold, int radius,
                              const ThinLineExtractor& extractor) {
  const int w = on.width(), h = on.height();
  PaddedImage<Pixel> difference(w, h);
  reference::subtract_saturating<Pixel>(on.view(), off.view(), difference.view());
  PaddedImage<std::uint8_t> binary(w, h), eroded(w, h), opened(w, h);
  reference::threshold_binary<Pixel>(difference.view(), threshold, 255, binary.view());
  reference::erode(binary.view(), {ElementShape::square, radius}, eroded.view());
  reference::dilate(eroded.view(), {ElementShape::square, radius}, opened.view());
  const BitImage& lines = extractor.lines();
  for (int y = 0; y < h; ++y) {
    bool any = false;
    for (int x = 0; x < w; ++x) {
      const bool expected = binary.at(x, y) != 0 && opened.at(x, y) == 0;
      ASSERT_EQ(lines.get(x, y), expected) << w << "x" << h << " r" << radius << " at " << x << "," << y;
      ASSERT_EQ(extractor.opened().get(x, y), opened.at(x, y) != 0) << x << "," << y;
      any |= expected;
    }
    ASSERT_EQ(lines.row_set(y), any) << "row flag " << y;
  }
}

TEST(ThinLines, KeepsTapeAndDropsLargeBrightAreas) {
  const int w = 120, h = 80;
  PaddedImage<std::uint8_t> on(w, h, 4), off(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool tape = (y >= 20 && y < 23 && x >= 10 && x < 70) || (x >= 90 && x < 93 && y >= 5 && y < 75);
      const bool lamp = x >= 20 && x < 50 && y >= 40 && y < 70;
      on.at(x, y) = tape || lamp ? 200 : 15;
      off.at(x, y) = 10;
    }
  }
  ThinLineExtractor extractor(w, h, 3);
  extractor.extract(on.view(), off.view(), 100);
  const BitImage& lines = extractor.lines();
  EXPECT_TRUE(lines.get(40, 21));    // horizontal tape, 3 px wide
  EXPECT_TRUE(lines.get(91, 50));    // vertical tape
  EXPECT_FALSE(lines.get(35, 55));   // lamp interior
  EXPECT_FALSE(lines.get(20, 40));   // lamp corner: the opening keeps a 30x30 square whole
  EXPECT_FALSE(lines.get(100, 10));  // background
  EXPECT_FALSE(lines.row_set(2));
  expect_matches_reference(on, off, std::uint8_t{100}, 3, extractor);
}

// Random masks of blobs, bars and noise against the references, at sizes that end inside a word
// and on one, radii up to the kernel's largest (on small images), and elements wider than the
// image.
TEST(ThinLines, MatchesReferenceExactly) {
  std::mt19937 rng(16);
  const int sizes[][2] = {{1, 1}, {64, 9}, {65, 40}, {130, 70}, {200, 33}, {37, 128}};
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1];
    for (const int radius : {0, 1, 2, 4, 6, 13, 40, 63}) {
      if (w * h * (2 * radius + 1) * (2 * radius + 1) > 4'000'000) continue;  // the reference's cost
      PaddedImage<std::uint8_t> on(w, h, 3), off(w, h, 3);
      test::fill_random(off, rng, 40);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) on.at(x, y) = off.at(x, y);
      }
      std::uniform_int_distribution<int> px(0, w - 1), py(0, h - 1), extent(0, 3 * radius + 4);
      for (int k = 0; k < 12; ++k) {  // rectangles: lamps, bars, tape
        const int x0 = px(rng), y0 = py(rng), x1 = std::min(w, x0 + 1 + extent(rng)), y1 = std::min(h, y0 + 1 + extent(rng));
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) on.at(x, y) = 250;
        }
      }
      for (int k = 0; k < w * h / 20; ++k) on.at(px(rng), py(rng)) = 200;  // isolated pixels
      ThinLineExtractor extractor(w, h, radius);
      extractor.extract(on.view(), off.view(), 50);
      expect_matches_reference(on, off, std::uint8_t{50}, radius, extractor);
      // A second frame through the same extractor: nothing of the first is left behind.
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) on.at(x, y) = (x + y) % 11 == 0 ? 255 : off.at(x, y);
      }
      extractor.extract(on.view(), off.view(), 50);
      expect_matches_reference(on, off, std::uint8_t{50}, radius, extractor);
    }
  }
}

TEST(ThinLines, SixteenBitInputAndNoAllocation) {
  PaddedImage<std::uint16_t> on(70, 32), off(70, 32);
  for (int x = 0; x < 70; ++x) on.at(x, 10) = 3000;
  for (int y = 0; y < 32; ++y) on.at(66, y) = 1001;
  for (int y = 12; y < 30; ++y) {
    for (int x = 5; x < 40; ++x) on.at(x, y) = 4095;
  }
  ThinLineExtractor extractor(70, 32, 2);
  test::AllocationCounter counter;
  extractor.extract(on.view(), off.view(), 1000);
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(extractor.lines().get(30, 10));
  EXPECT_TRUE(extractor.lines().get(66, 20));
  EXPECT_FALSE(extractor.lines().get(30, 11));
  EXPECT_FALSE(extractor.lines().get(20, 20));  // the block
  expect_matches_reference(on, off, std::uint16_t{1000}, 2, extractor);
}

// The tape mask from the shared frame pass's runs (the fused front end at the same threshold) is
// the mask of the extractor's own pass, for regions anywhere in the frame, cut mid-word or not.
TEST(ThinLines, FromTheSharedPassRunsAsFromItsOwnPass) {
  std::mt19937 rng(7);
  const int w = 300, h = 120;
  PaddedImage<std::uint8_t> on(w, h), off(w, h);
  test::fill_random(off, rng, 40);
  std::uniform_int_distribution<int> px(0, w - 1), py(0, h - 1), extent(1, 30);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) on.at(x, y) = off.at(x, y);
  }
  for (int k = 0; k < 40; ++k) {  // tape, lamps, isolated pixels
    const int x0 = px(rng), y0 = py(rng), x1 = std::min(w, x0 + extent(rng)), y1 = std::min(h, y0 + extent(rng) / 8 + 1);
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) on.at(x, y) = 230;
    }
  }
  for (int k = 0; k < 300; ++k) on.at(px(rng), py(rng)) = 200;
  FusedFrontEnd front_end({.width = w, .height = h});
  BlobList blobs;
  front_end.process(ImageView8(on.view()), ImageView8(off.view()), 50, blobs);
  for (const auto& [x0, y0, rw, rh] : {std::array<int, 4>{0, 0, w, h}, {13, 7, 200, 90}, {64, 0, 128, 120},
                                      {250, 100, 50, 20}, {1, 1, 1, 1}}) {
    ThinLineExtractor own(rw, rh, 3), shared(rw, rh, 3);
    own.extract(ImageView8(on.view()).region(x0, y0, rw, rh), ImageView8(off.view()).region(x0, y0, rw, rh), 50);
    shared.extract(front_end.runs(), x0, y0);
    for (int y = 0; y < rh; ++y) {
      ASSERT_EQ(shared.binary().row_set(y), own.binary().row_set(y)) << x0 << "," << y0 << " row " << y;
      ASSERT_EQ(shared.lines().row_set(y), own.lines().row_set(y)) << x0 << "," << y0 << " row " << y;
      for (int x = 0; x < rw; ++x) {
        ASSERT_EQ(shared.binary().get(x, y), own.binary().get(x, y)) << x0 << "," << y0 << " at " << x << "," << y;
        ASSERT_EQ(shared.lines().get(x, y), own.lines().get(x, y)) << x0 << "," << y0 << " at " << x << "," << y;
      }
    }
    test::AllocationCounter counter;
    shared.extract(front_end.runs(), x0, y0);
    EXPECT_EQ(counter.count(), 0u);
  }
}

TEST(ThinLines, RefusesAnElementWiderThanTheKernelTakes) {
  EXPECT_THROW(ThinLineExtractor(64, 64, ThinLineExtractor::kMaxRadius + 1), std::invalid_argument);
  EXPECT_THROW(ThinLineExtractor(64, 64, -1), std::invalid_argument);
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
