// The normalized errors' RMS pooled over scenes and its interval with the scene as the unit
// (scene_interval.hpp).

#include <gtest/gtest.h>

#include <vector>

#include "tests/survey/scene_interval.hpp"

namespace irloc::test {
namespace {

// A scene of `markers` markers whose normalized errors have RMS `rms` on every axis.
SceneSquares scene(double rms, int markers) {
  SceneSquares squares;
  squares.squares.fill(rms * rms * markers);
  squares.markers = markers;
  return squares;
}

TEST(SceneInterval, ScenesThatAgreeGiveTheirRmsAndANarrowInterval) {
  const PooledRms pooled = pooled_rms_over_scenes(std::vector<SceneSquares>(12, scene(0.8, 10)));
  for (std::size_t axis = 0; axis < 4; ++axis) {
    EXPECT_NEAR(pooled.rms[axis], 0.8, 1e-12);
    EXPECT_NEAR(pooled.low[axis], 0.8, 1e-12);
    EXPECT_NEAR(pooled.high[axis], 0.8, 1e-12);
    EXPECT_FALSE(pooled.interval_includes_one(axis));
  }
  EXPECT_EQ(pooled.scenes, 12);
  EXPECT_EQ(pooled.markers, 120);
}

// The same markers' errors, once spread over every scene and once in two scenes whose markers
// all share one large error: the same pooled RMS, but the second is two draws, not 120, and its
// interval holds 1 where the first does not.
TEST(SceneInterval, ErrorsSharedWithinAFewScenesWidenTheInterval) {
  std::vector<SceneSquares> spread(12, scene(0.8, 10));
  std::vector<SceneSquares> shared(10, scene(0.2, 10));
  const double loud = std::sqrt((0.64 * 120 - 0.04 * 100) / 20);
  shared.push_back(scene(loud, 10));
  shared.push_back(scene(loud, 10));
  const PooledRms narrow = pooled_rms_over_scenes(spread), wide = pooled_rms_over_scenes(shared);
  EXPECT_NEAR(wide.rms[2], narrow.rms[2], 1e-9);
  EXPECT_LT(wide.low[2], 0.5);
  EXPECT_GT(wide.high[2], 1.0);
  EXPECT_TRUE(wide.interval_includes_one(2));
}

TEST(SceneInterval, ScenesWithoutMarkersAreNotUnits) {
  const PooledRms pooled = pooled_rms_over_scenes({scene(1.0, 5), SceneSquares{}, scene(1.0, 5)});
  EXPECT_EQ(pooled.scenes, 2);
  EXPECT_NEAR(pooled.rms[0], 1.0, 1e-12);
  EXPECT_EQ(pooled_rms_over_scenes({SceneSquares{}}).scenes, 0);
}

}  // namespace
}  // namespace irloc::test
