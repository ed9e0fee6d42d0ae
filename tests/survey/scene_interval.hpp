#pragma once
// The normalized errors' RMS per axis pooled over surveyed scenes, with an interval that takes the
// scene as the unit. A scene's markers share most of their error along the chain from its fixed
// marker (docs/survey.md, "How far one drive's RMS scatters"), so they are not independent draws
// and an interval over markers would be far too narrow. The interval is the percentile bootstrap's
// over scenes: the scenes drawn with replacement, each draw's pooled RMS, its 2.5 and 97.5 %
// quantiles (a fixed random stream: the same scenes give the same interval).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace irloc::test {

// One scene's squared normalized errors summed per axis (x, y, z, yaw) over its markers.
struct SceneSquares {
  std::array<double, 4> squares{};
  int markers = 0;
};

struct PooledRms {
  std::array<double, 4> rms{}, low{}, high{};  // per axis: over every scene, and the 95 % interval
  int scenes = 0, markers = 0;                 // the scenes with a marker, and their markers
  bool interval_includes_one(std::size_t axis) const { return low[axis] <= 1 && high[axis] >= 1; }
};

// The normalized errors' RMS per axis over every marker of the scenes; 0 without a marker.
inline std::array<double, 4> rms_over_scenes(const std::vector<SceneSquares>& scenes) {
  std::array<double, 4> squares{}, rms{};
  int markers = 0;
  for (const SceneSquares& scene : scenes) {
    for (std::size_t axis = 0; axis < 4; ++axis) squares[axis] += scene.squares[axis];
    markers += scene.markers;
  }
  if (markers == 0) return rms;
  for (std::size_t axis = 0; axis < 4; ++axis) rms[axis] = std::sqrt(squares[axis] / markers);
  return rms;
}

inline PooledRms pooled_rms_over_scenes(const std::vector<SceneSquares>& all) {
  constexpr int kResamples = 4000;
  std::vector<SceneSquares> scenes;
  for (const SceneSquares& scene : all) {
    if (scene.markers > 0) scenes.push_back(scene);
  }
  PooledRms pooled;
  pooled.scenes = static_cast<int>(scenes.size());
  if (scenes.empty()) return pooled;
  const auto rms_of = [](const SceneSquares& sum, std::size_t axis) { return std::sqrt(sum.squares[axis] / sum.markers); };
  pooled.rms = rms_over_scenes(scenes);
  for (const SceneSquares& scene : scenes) pooled.markers += scene.markers;
  std::array<std::vector<double>, 4> resampled;
  std::mt19937 random(1);
  std::uniform_int_distribution<std::size_t> pick(0, scenes.size() - 1);
  for (int k = 0; k < kResamples; ++k) {
    SceneSquares draw;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      const SceneSquares& scene = scenes[pick(random)];
      for (std::size_t axis = 0; axis < 4; ++axis) draw.squares[axis] += scene.squares[axis];
      draw.markers += scene.markers;
    }
    for (std::size_t axis = 0; axis < 4; ++axis) resampled[axis].push_back(rms_of(draw, axis));
  }
  for (std::size_t axis = 0; axis < 4; ++axis) {
    std::vector<double>& values = resampled[axis];
    std::sort(values.begin(), values.end());
    pooled.low[axis] = values[static_cast<std::size_t>(0.025 * (kResamples - 1))];
    pooled.high[axis] = values[static_cast<std::size_t>(0.975 * (kResamples - 1))];
  }
  return pooled;
}

}  // namespace irloc::test
