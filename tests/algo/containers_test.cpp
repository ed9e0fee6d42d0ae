#include <cstdint>

#include <gtest/gtest.h>

#include "algo/core/image.hpp"
#include "algo/core/image_view.hpp"
#include "algo/core/scratch_arena.hpp"
#include "algo/core/static_vector.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

TEST(ImageView, AddressesPaddedRowsByStride) {
  std::uint16_t pixels[3 * 5] = {};
  MutableImageView16 view(pixels, 4, 3, 5);
  view.at(3, 2) = 7;
  EXPECT_EQ(pixels[2 * 5 + 3], 7);
  EXPECT_EQ(view.row(1), pixels + 5);
  const MutableImageView16 roi = view.region(1, 1, 3, 2);
  roi.at(2, 1) = 9;
  EXPECT_EQ(pixels[2 * 5 + 3], 9);
  EXPECT_EQ(roi.stride(), 5);
  const ImageView16 read_only = view;
  EXPECT_EQ(read_only.at(3, 2), 9);
  EXPECT_TRUE(ImageView8().empty());
}

TEST(ImageView, GrayVariantReportsSize) {
  Image8 image(7, 3);
  const GrayImageView gray = ImageView8(image.view());
  EXPECT_EQ(width_of(gray), 7);
  EXPECT_EQ(height_of(gray), 3);
}

TEST(StaticVector, CountsWhatDidNotFit) {
  StaticVector<int, 3> v;
  EXPECT_TRUE(v.push_back(1));
  EXPECT_TRUE(v.push_back(2));
  EXPECT_TRUE(v.push_back(3));
  EXPECT_FALSE(v.push_back(4));
  EXPECT_FALSE(v.push_back(5));
  EXPECT_EQ(v.size(), 3u);
  EXPECT_EQ(v.dropped(), 2u);
  EXPECT_TRUE(v.overflowed());
  int sum = 0;
  for (int x : v) sum += x;
  EXPECT_EQ(sum, 6);
  v.clear();
  EXPECT_TRUE(v.empty());
  EXPECT_FALSE(v.overflowed());
}

TEST(ScratchArena, HandsOutAlignedPiecesAndReportsExhaustion) {
  ScratchArena arena(1024);
  const std::span<std::uint8_t> bytes = arena.allocate<std::uint8_t>(3);
  const std::span<double> doubles = arena.allocate<double>(10);
  ASSERT_EQ(bytes.size(), 3u);
  ASSERT_EQ(doubles.size(), 10u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(doubles.data()) % alignof(double), 0u);
  EXPECT_GE(reinterpret_cast<std::byte*>(doubles.data()), reinterpret_cast<std::byte*>(bytes.data() + 3));
  EXPECT_FALSE(arena.exhausted());

  EXPECT_TRUE(arena.allocate<std::uint8_t>(2000).empty());
  EXPECT_TRUE(arena.exhausted());
  const std::size_t peak = arena.high_water();
  EXPECT_GE(peak, 83u);

  arena.reset();
  EXPECT_FALSE(arena.exhausted());
  EXPECT_EQ(arena.used(), 0u);
  EXPECT_EQ(arena.allocate<std::uint8_t>(1024).size(), 1024u);
  EXPECT_EQ(arena.high_water(), 1024u);
}

TEST(ScratchArena, AllocatesNothingAfterConstruction) {
  ScratchArena arena(1 << 16);
  test::AllocationCounter counter;
  for (int frame = 0; frame < 100; ++frame) {
    arena.reset();
    ASSERT_FALSE(arena.allocate<std::int32_t>(1000).empty());
    ASSERT_FALSE(arena.allocate<std::uint16_t>(2000).empty());
  }
  EXPECT_EQ(counter.count(), 0u);
}

TEST(AllocationCounter, SeesContainerAllocations) {
  test::AllocationCounter counter;
  std::vector<int> grows;
  grows.push_back(1);
  EXPECT_GE(counter.count(), 1u);
}

}  // namespace
}  // namespace irloc
