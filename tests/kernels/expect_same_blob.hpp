#pragma once
// Two blobs' statistics are the same, field by field (index names the blob in a failure).
#include <cstddef>

#include <gtest/gtest.h>

#include "algo/kernels/blob.hpp"

namespace irloc::test {

inline void expect_same_blob(const Blob& a, const Blob& b, std::size_t index) {
  SCOPED_TRACE(testing::Message() << "blob " << index);
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.x_min, b.x_min);
  EXPECT_EQ(a.y_min, b.y_min);
  EXPECT_EQ(a.x_max, b.x_max);
  EXPECT_EQ(a.y_max, b.y_max);
  EXPECT_EQ(a.sum_x, b.sum_x);
  EXPECT_EQ(a.sum_y, b.sum_y);
  EXPECT_EQ(a.sum_i, b.sum_i);
  EXPECT_EQ(a.sum_ix, b.sum_ix);
  EXPECT_EQ(a.sum_iy, b.sum_iy);
  EXPECT_EQ(a.sum_ixx, b.sum_ixx);
  EXPECT_EQ(a.sum_iyy, b.sum_iyy);
  EXPECT_EQ(a.sum_ixy, b.sum_ixy);
  EXPECT_EQ(a.peak, b.peak);
}

}  // namespace irloc::test
