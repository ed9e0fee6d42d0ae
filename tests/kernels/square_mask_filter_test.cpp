// The running-count square erosion and dilation of binary masks against the plain references
// (reference_kernels: the min / max over every pixel of the element inside the image).
#include "algo/kernels/square_mask_filter.hpp"

#include <algorithm>
#include <cstdint>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "tests/kernels/kernel_test_images.hpp"
#include "tests/kernels/reference_kernels.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::PaddedImage;
using Operation = SquareMaskFilter::Operation;

void reference_filter(Operation operation, ImageView8 in, int radius, MutableImageView8 out) {
  if (operation == Operation::erode) {
    reference::erode(in, {ElementShape::square, radius}, out);
  } else {
    reference::dilate(in, {ElementShape::square, radius}, out);
  }
}

// Widths below, at and above one 16- and 32-byte vector and with a partial last vector; radii
// from 0 to beyond the image; sparse, half and nearly full masks; images with padded rows.
TEST(SquareMaskFilter, MatchesTheReferenceOnRandomMasks) {
  std::mt19937 rng(27);
  const int sizes[][3] = {{1, 1, 0}, {2, 9, 1}, {17, 3, 0}, {33, 20, 5}, {64, 31, 0}, {70, 41, 3}, {131, 17, 0}};
  for (const auto& size : sizes) {
    const int w = size[0], h = size[1], pad = size[2];
    for (const int percent : {3, 50, 97}) {
      PaddedImage<std::uint8_t> in(w, h, pad);
      test::fill_random_mask(in, rng, percent);
      for (const int radius : {0, 1, 2, 3, 4, 5, 8, 12, 20}) {
        for (const Operation operation : {Operation::erode, Operation::dilate}) {
          SquareMaskFilter filter(140, radius, operation);
          PaddedImage<std::uint8_t> fast(w, h, pad, 0x33), slow(w, h, pad, 0x33);
          filter.apply(in.view(), fast.view());
          reference_filter(operation, in.view(), radius, slow.view());
          const char* name = operation == Operation::erode ? "erode " : "dilate ";
          ASSERT_EQ(fast.storage(), slow.storage()) << name << w << "x" << h << " " << percent << " % r" << radius;
          // Row by row, as the background's pass asks them: the same rows.
          for (int y = 0; y < h; ++y) {
            const std::uint8_t* row = filter.row(in.view(), y);
            ASSERT_TRUE(std::equal(row, row + w, slow.view().row(y))) << name << "row " << y;
          }
          // Rows skipped, singly and two in a row (their turns taken): the rows asked are the same.
          for (int y = 0; y < h; ++y) {
            if (y % 5 == 1 || y % 7 >= 5) {
              filter.skip_row(in.view(), y);
              continue;
            }
            const std::uint8_t* row = filter.row(in.view(), y);
            ASSERT_TRUE(std::equal(row, row + w, slow.view().row(y))) << name << "row " << y << " after skipped rows";
          }
        }
      }
    }
  }
}

// A narrower image after a wider one: the end of the wider row is not read as the narrower's
// neighbour.
TEST(SquareMaskFilter, ANarrowerImageAfterAWiderOneIsFilteredOnItsOwn) {
  for (const Operation operation : {Operation::erode, Operation::dilate}) {
    SquareMaskFilter filter(96, 5, operation);
    PaddedImage<std::uint8_t> wide(96, 12), narrow(40, 12), fast(40, 12), slow(40, 12), wide_out(96, 12);
    wide.fill(operation == Operation::erode ? 0 : 255);
    narrow.fill(operation == Operation::erode ? 255 : 0);
    filter.apply(wide.view(), wide_out.view());
    filter.apply(narrow.view(), fast.view());
    reference_filter(operation, narrow.view(), 5, slow.view());
    EXPECT_EQ(fast.storage(), slow.storage());
  }
}

TEST(SquareMaskFilter, RefusesARadiusItCannotCount) {
  EXPECT_THROW(SquareMaskFilter(64, SquareMaskFilter::kMaxRadius + 1, Operation::dilate), std::invalid_argument);
  EXPECT_THROW(SquareMaskFilter(64, -1, Operation::erode), std::invalid_argument);
  EXPECT_NO_THROW(SquareMaskFilter(64, SquareMaskFilter::kMaxRadius, Operation::erode));
}

TEST(SquareMaskFilter, AllocatesNothing) {
  SquareMaskFilter erode(64, 2, Operation::erode), dilate(64, 12, Operation::dilate);
  PaddedImage<std::uint8_t> in(64, 64), out(64, 64);
  test::AllocationCounter counter;
  erode.apply(in.view(), out.view());
  for (int y = 0; y < 64; ++y) dilate.row(in.view(), y);
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace irloc
