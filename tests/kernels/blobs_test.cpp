// Connected components to blob statistics: the fused front end and the mask labeller against the
// flood-fill reference, edge cases, overflow reports and zero allocations per frame.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "algo/kernels/blob_labeller.hpp"
#include "algo/kernels/difference.hpp"
#include "algo/kernels/fused_front_end.hpp"
#include "tests/kernels/reference_kernels.hpp"
#include "algo/kernels/threshold.hpp"
#include "tests/kernels/expect_same_blob.hpp"
#include "tests/kernels/kernel_test_images.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::expect_same_blob;
using test::PaddedImage;

template <typename Pixel>
void expect_matches_reference(const BlobList& blobs, const BlobCounters& counters, const PaddedImage<Pixel>& on,
                              const PaddedImage<Pixel>& off, Pixel threshold) {
  PaddedImage<Pixel> difference(on.width(), on.height());
  reference::subtract_saturating<Pixel>(on.view(), off.view(), difference.view());
  const std::vector<Blob> expected = reference::blobs<Pixel>(difference.view(), threshold);
  // Beyond kMaxBlobs the first ones in raster order are kept and the rest counted.
  const std::size_t kept = std::min(expected.size(), kMaxBlobs);
  ASSERT_EQ(blobs.size(), kept);
  EXPECT_EQ(counters.components, expected.size());
  EXPECT_EQ(counters.blobs_dropped, expected.size() - kept);
  std::uint32_t area = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (i < kept) expect_same_blob(blobs[i], expected[i], i);
    area += expected[i].area;
  }
  EXPECT_EQ(counters.foreground_pixels, area);
}

TEST(FusedFrontEnd, MatchesReferenceOnStrobePairs8Bit) {
  std::mt19937 rng(1);
  for (const int width : {1, 5, 33, 97, 160}) {
    const int height = width == 1 ? 1 : 61;
    PaddedImage<std::uint8_t> on(width, height, width % 7), off(width, height, width % 5);
    test::make_strobe_pair(on, off, rng, width / 8 + 1);
    FusedFrontEnd front_end({.width = width, .height = height});
    BlobList blobs;
    for (const std::uint8_t threshold : {std::uint8_t{0}, std::uint8_t{6}, std::uint8_t{30}, std::uint8_t{120}}) {
      SCOPED_TRACE(testing::Message() << width << "x" << height << " t=" << int{threshold});
      const BlobCounters counters = front_end.process(on.view(), off.view(), threshold, blobs);
      expect_matches_reference(blobs, counters, on, off, threshold);
    }
  }
}

TEST(FusedFrontEnd, MatchesReferenceOnRandomNoise) {
  // Dense random foreground: many merging, diagonal-only and U-shaped components.
  std::mt19937 rng(2);
  PaddedImage<std::uint8_t> on(77, 53, 3), off(77, 53);
  test::fill_random(on, rng, 255);
  test::fill_random(off, rng, 60);
  FusedFrontEnd front_end({.width = 77, .height = 53});
  BlobList blobs;
  for (const std::uint8_t threshold : {std::uint8_t{100}, std::uint8_t{160}, std::uint8_t{200}}) {
    const BlobCounters counters = front_end.process(on.view(), off.view(), threshold, blobs);
    expect_matches_reference(blobs, counters, on, off, threshold);
  }
}

TEST(FusedFrontEnd, MatchesReferenceAt12And16Bits) {
  std::mt19937 rng(3);
  // Widths of one and three full 64-pixel blocks and a rest.
  for (const auto& [bits, width] : {std::pair{12, 90}, std::pair{16, 90}, std::pair{12, 203}}) {
    const int max_value = (1 << bits) - 1;
    PaddedImage<std::uint16_t> on(width, 70, 6), off(width, 70, 2);
    test::make_strobe_pair(on, off, rng, 12, max_value);
    FusedFrontEnd front_end({.width = width, .height = 70, .value_bits = bits});
    BlobList blobs;
    const auto threshold = static_cast<std::uint16_t>(30 << (bits - 8));
    const BlobCounters counters = front_end.process(on.view(), off.view(), threshold, blobs);
    EXPECT_GT(blobs.size(), 3u);
    expect_matches_reference(blobs, counters, on, off, threshold);
  }
}

TEST(FusedFrontEnd, CentroidsAndMomentsMatchADoubleReference) {
  std::mt19937 rng(4);
  PaddedImage<std::uint8_t> on(200, 150, 8), off(200, 150);
  test::make_strobe_pair(on, off, rng, 25);
  const std::uint8_t threshold = 20;
  FusedFrontEnd front_end({.width = 200, .height = 150});
  BlobList blobs;
  front_end.process(on.view(), off.view(), threshold, blobs);
  ASSERT_GT(blobs.size(), 10u);
  PaddedImage<std::int32_t> labels(200, 150);
  front_end.paint_labels(labels.view());
  std::vector<double> si(blobs.size()), sx(blobs.size()), sy(blobs.size()), sxx(blobs.size()), syy(blobs.size()),
      sxy(blobs.size());
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 200; ++x) {
      const int label = labels.at(x, y);
      if (label == 0) continue;
      const auto i = static_cast<std::size_t>(label - 1);
      const double value = on.at(x, y) - off.at(x, y);
      si[i] += value;
      sx[i] += value * x;
      sy[i] += value * y;
    }
  }
  for (std::size_t i = 0; i < blobs.size(); ++i) {
    const double cx = sx[i] / si[i];
    const double cy = sy[i] / si[i];
    EXPECT_NEAR(blobs[i].centroid_x(), cx, 1e-9);
    EXPECT_NEAR(blobs[i].centroid_y(), cy, 1e-9);
    EXPECT_NEAR(blobs[i].centroid_x_q8().to_double(), cx, 1.0 / 512 + 1e-12);
    EXPECT_NEAR(blobs[i].centroid_y_q8().to_double(), cy, 1.0 / 512 + 1e-12);
    EXPECT_NEAR(blobs[i].mean_intensity(), si[i] / blobs[i].area, 1e-9);
  }
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 200; ++x) {
      const int label = labels.at(x, y);
      if (label == 0) continue;
      const auto i = static_cast<std::size_t>(label - 1);
      const double value = on.at(x, y) - off.at(x, y);
      const double dx = x - sx[i] / si[i];
      const double dy = y - sy[i] / si[i];
      sxx[i] += value * dx * dx;
      syy[i] += value * dy * dy;
      sxy[i] += value * dx * dy;
    }
  }
  for (std::size_t i = 0; i < blobs.size(); ++i) {
    EXPECT_NEAR(blobs[i].mu_xx(), sxx[i] / si[i], 1e-9);
    EXPECT_NEAR(blobs[i].mu_yy(), syy[i] / si[i], 1e-9);
    EXPECT_NEAR(blobs[i].mu_xy(), sxy[i] / si[i], 1e-9);
  }
}

TEST(Blob, OrientationAndElongationOfAnEllipse) {
  // A filled ellipse, semi-axes 12 and 4, major axis at 30 degrees (toward +y, image y down).
  const double angle = std::numbers::pi / 6;
  PaddedImage<std::uint8_t> mask(64, 64);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const double u = (x - 32) * std::cos(angle) + (y - 32) * std::sin(angle);
      const double v = -(x - 32) * std::sin(angle) + (y - 32) * std::cos(angle);
      if ((u / 12) * (u / 12) + (v / 4) * (v / 4) <= 1) mask.at(x, y) = 255;
    }
  }
  BlobLabeller labeller(1024);
  BlobList blobs;
  labeller.label(mask.view(), {}, blobs);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_NEAR(blobs[0].orientation(), angle, 0.02);
  EXPECT_NEAR(blobs[0].elongation(), 3.0, 0.1);  // axis ratio 12 / 4
  EXPECT_NEAR(blobs[0].centroid_x(), 32.0, 1e-9);
  EXPECT_NEAR(blobs[0].centroid_y(), 32.0, 1e-9);
  // A one-pixel line is infinitely elongated.
  PaddedImage<std::uint8_t> line(20, 5);
  for (int x = 2; x < 18; ++x) line.at(x, 2) = 255;
  labeller.label(line.view(), {}, blobs);
  EXPECT_TRUE(std::isinf(blobs[0].elongation()));
  EXPECT_NEAR(blobs[0].orientation(), 0.0, 1e-12);
}

TEST(FusedFrontEnd, EdgeCases) {
  BlobList blobs;
  {  // 1x1 with and without a pixel
    PaddedImage<std::uint8_t> on(1, 1), off(1, 1);
    FusedFrontEnd front_end({.width = 1, .height = 1});
    EXPECT_EQ(front_end.process(on.view(), off.view(), 0, blobs).components, 0u);
    on.at(0, 0) = 9;
    front_end.process(on.view(), off.view(), 0, blobs);
    ASSERT_EQ(blobs.size(), 1u);
    EXPECT_EQ(blobs[0].area, 1u);
    EXPECT_EQ(blobs[0].peak, 9u);
    EXPECT_EQ(blobs[0].centroid_x_q8().raw(), 0);
  }
  {  // all 0, then all 255 against 0: one blob, the whole frame
    PaddedImage<std::uint8_t> on(45, 31, 3), off(45, 31, 1);
    FusedFrontEnd front_end({.width = 45, .height = 31});
    EXPECT_EQ(front_end.process(on.view(), off.view(), 0, blobs).foreground_pixels, 0u);
    EXPECT_TRUE(blobs.empty());
    on.fill(255);
    const BlobCounters counters = front_end.process(on.view(), off.view(), 254, blobs);
    ASSERT_EQ(blobs.size(), 1u);
    EXPECT_EQ(counters.runs, 31u);
    EXPECT_EQ(blobs[0].area, 45u * 31u);
    EXPECT_EQ(blobs[0].width(), 45);
    EXPECT_EQ(blobs[0].height(), 31);
    EXPECT_DOUBLE_EQ(blobs[0].centroid_x(), 22.0);
    EXPECT_DOUBLE_EQ(blobs[0].centroid_y(), 15.0);
    EXPECT_EQ(blobs[0].peak, 255u);
    // on == off: nothing, whatever the level
    off.fill(255);
    EXPECT_EQ(front_end.process(on.view(), off.view(), 0, blobs).foreground_pixels, 0u);
  }
  {  // a blob touching every border: the frame's rim plus a diagonal, and an isolated inner dot
    PaddedImage<std::uint8_t> on(40, 30, 2), off(40, 30);
    for (int x = 0; x < 40; ++x) on.at(x, 0) = on.at(x, 29) = 100;
    for (int y = 0; y < 30; ++y) on.at(0, y) = on.at(39, y) = 100;
    for (int k = 5; k < 25; ++k) on.at(k + 5, k) = 50;  // touches nothing
    on.at(20, 3) = 70;
    FusedFrontEnd front_end({.width = 40, .height = 30});
    const BlobCounters counters = front_end.process(on.view(), off.view(), 10, blobs);
    expect_matches_reference(blobs, counters, on, off, std::uint8_t{10});
    ASSERT_EQ(blobs.size(), 3u);
    EXPECT_EQ(blobs[0].area, 2u * 40u + 2u * 28u);
    EXPECT_EQ(blobs[0].width(), 40);
    EXPECT_EQ(blobs[0].height(), 30);
  }
}

TEST(FusedFrontEnd, ReportsMoreBlobsThanTheMaximum) {
  // Isolated single pixels on a 3-pixel grid: 30 x 20 = 600 components for 256 slots.
  PaddedImage<std::uint8_t> on(90, 60), off(90, 60);
  for (int y = 0; y < 60; y += 3) {
    for (int x = 0; x < 90; x += 3) on.at(x, y) = 80;
  }
  FusedFrontEnd front_end({.width = 90, .height = 60});
  BlobList blobs;
  const BlobCounters counters = front_end.process(on.view(), off.view(), 10, blobs);
  EXPECT_EQ(counters.components, 600u);
  EXPECT_EQ(blobs.size(), kMaxBlobs);
  EXPECT_EQ(counters.blobs_dropped, 600u - kMaxBlobs);
  EXPECT_EQ(blobs.dropped(), counters.blobs_dropped);
  EXPECT_EQ(counters.foreground_pixels, 600u);
  // The kept ones are the first in raster order.
  EXPECT_EQ(blobs[0].x_min, 0);
  EXPECT_EQ(blobs[kMaxBlobs - 1].y_min, 3 * static_cast<int>((kMaxBlobs - 1) / 30));
}

TEST(FusedFrontEnd, ReportsRunOverflowAndSmallBlobs) {
  PaddedImage<std::uint8_t> on(50, 10), off(50, 10);
  for (int x = 0; x < 50; x += 2) on.at(x, 1) = 90;  // 25 runs in row 1
  for (int x = 10; x < 20; ++x) on.at(x, 5) = on.at(x, 6) = 90;  // one 20-pixel blob
  FusedFrontEnd small_table({.width = 50, .height = 10, .max_runs = 10});
  BlobList blobs;
  BlobCounters counters = small_table.process(on.view(), off.view(), 10, blobs);
  EXPECT_EQ(counters.runs, 10u);
  EXPECT_EQ(counters.runs_dropped, 15u + 2u);
  EXPECT_EQ(counters.foreground_pixels, 25u + 20u);  // counted even when their runs are not kept
  EXPECT_EQ(blobs.size(), 10u);
  FusedFrontEnd filtered({.width = 50, .height = 10, .min_area = 2});
  counters = filtered.process(on.view(), off.view(), 10, blobs);
  EXPECT_EQ(counters.components, 26u);
  EXPECT_EQ(counters.blobs_too_small, 25u);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_EQ(blobs[0].area, 20u);
}

TEST(FusedFrontEnd, RejectsFramesTooLargeForExactSums) {
  EXPECT_THROW(FusedFrontEnd({.width = 8192, .height = 8192, .value_bits = 16}), std::invalid_argument);
  EXPECT_THROW(FusedFrontEnd({.width = 0, .height = 10}), std::invalid_argument);
  EXPECT_NO_THROW(FusedFrontEnd({.width = 2048, .height = 2048, .max_runs = 16, .value_bits = 16}));
}

TEST(FusedFrontEnd, AllocatesNothingPerFrame) {
  std::mt19937 rng(6);
  PaddedImage<std::uint8_t> on(128, 96), off(128, 96);
  PaddedImage<std::uint16_t> on16(128, 96), off16(128, 96);
  test::make_strobe_pair(on, off, rng, 20);
  test::make_strobe_pair(on16, off16, rng, 20, 1023);
  FusedFrontEnd front_end({.width = 128, .height = 96, .value_bits = 10});
  BlobList blobs;
  test::AllocationCounter counter;
  for (int frame = 0; frame < 3; ++frame) {
    front_end.process(on.view(), off.view(), 20, blobs);
    front_end.process(on16.view(), off16.view(), 80, blobs);
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_GT(blobs.size(), 5u);
}

TEST(BlobLabeller, MatchesReferenceOnMasksWithIntensity) {
  std::mt19937 rng(8);
  PaddedImage<std::uint8_t> on(101, 67, 5), off(101, 67, 5), difference(101, 67, 1), mask(101, 67, 3);
  test::make_strobe_pair(on, off, rng, 15);
  subtract_saturating(on.view(), off.view(), difference.view());
  threshold_binary(difference.view(), 25, 255, mask.view());
  BlobLabeller labeller(4096);
  BlobList blobs;
  const BlobCounters counters = labeller.label(mask.view(), difference.view(), {}, blobs);
  // The fused path on the same pair must agree blob for blob.
  FusedFrontEnd front_end({.width = 101, .height = 67});
  BlobList fused;
  front_end.process(on.view(), off.view(), 25, fused);
  ASSERT_EQ(blobs.size(), fused.size());
  for (std::size_t i = 0; i < blobs.size(); ++i) expect_same_blob(blobs[i], fused[i], i);
  expect_matches_reference(blobs, counters, on, off, std::uint8_t{25});
  test::AllocationCounter allocations;
  labeller.label(mask.view(), {}, blobs);
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(blobs[0].peak, 255u);  // without an intensity image I is the mask value
}

}  // namespace
}  // namespace irloc
