// EndFaceLooks (end_face_looks.hpp): the front told from the back by the end faces' band shades.
#include "algo/markers/outside_in/end_face_looks.hpp"

#include <gtest/gtest.h>

namespace irloc::test {
namespace {

using outside_in::EndFaceLooks;
using outside_in::EndView;

// Issue 27's robot over its top's shade: a dark strip over the lower third of its front.
EndView view(std::array<double, 6> ratio, int side = 1) { return EndView{side, ratio}; }
const EndView kFront = view({0.22, 0.22, 0.90, 0.90, 0.90, 0.90});
const EndView kBack = view({0.80, 0.80, 0.80, 0.80, 0.80, 0.80});

void learn(EndFaceLooks& looks, const EndView& end, bool front, int times) {
  for (int i = 0; i < times; ++i) looks.learn(end, front);
}

TEST(EndFaceLooks, NothingLearnedTellsNothing) {
  EndFaceLooks looks;
  EXPECT_EQ(looks.tell(kFront), 0);
  learn(looks, kBack, false, EndFaceLooks::kMinViews - 1);
  EXPECT_EQ(looks.tell(kFront), 0);
}

TEST(EndFaceLooks, BothEndsLearnedTellEachAndNotAViewBetweenThem) {
  EndFaceLooks looks;
  learn(looks, kFront, true, EndFaceLooks::kMinViews);
  learn(looks, kBack, false, EndFaceLooks::kMinViews);
  EXPECT_EQ(looks.tell(kFront), 1);
  EXPECT_EQ(looks.tell(kBack), -1);
  EXPECT_EQ(looks.tell(view({0.5, 0.5, 0.85, 0.85, 0.85, 0.85})), 0);
  EXPECT_EQ(looks.tell(view({0.22, 0.22, 0.90, 0.90, 0.90, 0.90}, 0)), 0) << "no end seen";
}

TEST(EndFaceLooks, EndsThatLookAlikeTellNothing) {
  EndFaceLooks looks;
  learn(looks, kBack, true, EndFaceLooks::kMinViews);
  learn(looks, view({0.82, 0.82, 0.82, 0.82, 0.82, 0.82}), false, EndFaceLooks::kMinViews);
  EXPECT_EQ(looks.tell(kBack), 0);
  EXPECT_EQ(looks.tell(kFront), 0);
}

// With the back alone learned, a view far from it is the front; a view like it may be a front that
// looks alike, and tells nothing.
TEST(EndFaceLooks, OneEndLearnedTellsOnlyTheOtherEndByItsDifference) {
  EndFaceLooks looks;
  learn(looks, kBack, false, EndFaceLooks::kMinViews);
  EXPECT_EQ(looks.tell(kFront), 1);
  EXPECT_EQ(looks.tell(kBack), 0);
  EXPECT_EQ(looks.tell(view({0.88, 0.88, 0.88, 0.88, 0.88, 0.88})), 0) << "0.08 from the back: not far enough";
}

TEST(EndFaceLooks, ViewsWithNoEndAreNotLearned) {
  EndFaceLooks looks;
  learn(looks, view({0.22, 0.22, 0.90, 0.90, 0.90, 0.90}, 0), true, EndFaceLooks::kMinViews);
  EXPECT_EQ(looks.tell(kBack), 0);
}

}  // namespace
}  // namespace irloc::test
