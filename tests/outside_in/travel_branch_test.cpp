// The branch of a track begun mid-drive, from its travel (travel_branch.hpp).
#include "algo/markers/outside_in/travel_branch.hpp"

#include <numbers>

#include <gtest/gtest.h>

namespace irloc::outside_in {
namespace {

// Steps of 5 cm along +x while the heading is `yaw`; how many of them asked for a half turn.
int drive(TravelBranch& branch, double metres, double yaw, double direction = 1) {
  int turns = 0;
  for (double done = 0; done < metres - 1e-9; done += 0.05) turns += branch.add({direction * 0.05, 0}, yaw);
  return turns;
}

TEST(TravelBranch, AMetreForwardConfirmsTheHeading) {
  TravelBranch branch;
  EXPECT_EQ(drive(branch, 0.95, 0), 0);
  EXPECT_FALSE(branch.confirmed());
  EXPECT_EQ(drive(branch, 0.05, 0), 0);
  EXPECT_TRUE(branch.confirmed());
}

TEST(TravelBranch, AMetreAgainstTheHeadingTurnsItOnceThenConfirms) {
  TravelBranch branch;
  // The robot drives toward -x while the track's heading says +x (found while reversing, or the
  // track took its first travel the wrong way).
  EXPECT_EQ(drive(branch, 1.0, 0, -1), 1);
  EXPECT_TRUE(branch.confirmed());
  // Once turned, the same travel is forward: no second turn.
  EXPECT_EQ(drive(branch, 1.0, std::numbers::pi, -1), 0);
}

TEST(TravelBranch, ADriveBackAndForthDecidesNothing) {
  TravelBranch branch;
  for (int leg = 0; leg < 4; ++leg) EXPECT_EQ(drive(branch, 0.6, 0, leg % 2 ? -1 : 1), 0);
  EXPECT_FALSE(branch.confirmed());  // 1.2 m each way: not 4:1
}

TEST(TravelBranch, SidewaysTravelCountsNothing) {
  TravelBranch branch;
  for (int i = 0; i < 100; ++i) EXPECT_FALSE(branch.add({0, 0.05}, 0));
  EXPECT_FALSE(branch.confirmed());
}

TEST(TravelBranch, AReacquiredTracksBranchIsConfirmedAsItWas) {
  TravelBranch branch;
  branch.confirm();
  EXPECT_EQ(drive(branch, 2.0, 0, -1), 0);  // a long reverse after it turns nothing
  EXPECT_TRUE(branch.confirmed());
}

}  // namespace
}  // namespace irloc::outside_in
